// The protobuf wire format, just enough to read and rewrite an ONNX model's graph (onnx_fold.h):
// a message is a list of fields, each a field number, a wire type and its payload. Unknown fields
// pass through untouched, so parse -> serialize gives the same bytes back.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace wardmap::semantics::wire {

enum WireType : std::uint32_t { kVarint = 0, kFixed64 = 1, kLengthDelimited = 2, kFixed32 = 5 };

struct Field {
  std::uint32_t number = 0;
  std::uint32_t type = kVarint;
  std::uint64_t varint = 0;  // kVarint
  std::string bytes;         // kLengthDelimited payload, or the 8 / 4 little-endian bytes of a fixed field
};

// Throws std::runtime_error on truncated input, a field number 0 or a group (wire types 3 and 4).
std::vector<Field> parse(std::string_view message);
std::string serialize(const std::vector<Field>& fields);

Field varint_field(std::uint32_t number, std::uint64_t value);
Field bytes_field(std::uint32_t number, std::string bytes);

// The payload of every length-delimited field `number`, as text (names, sub-messages).
std::vector<std::string> strings(const std::vector<Field>& fields, std::uint32_t number);
// The varint values of field `number`, packed (one length-delimited field) or not.
std::vector<std::int64_t> varints(const std::vector<Field>& fields, std::uint32_t number);

}  // namespace wardmap::semantics::wire
