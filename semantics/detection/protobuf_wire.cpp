#include "semantics/detection/protobuf_wire.h"

#include <stdexcept>

namespace wardmap::semantics::wire {

namespace {

std::uint64_t read_varint(std::string_view in, size_t& pos) {
  std::uint64_t value = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (pos >= in.size()) throw std::runtime_error("protobuf: truncated varint");
    const auto byte = static_cast<std::uint8_t>(in[pos++]);
    value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
    if (byte < 0x80) return value;
  }
  throw std::runtime_error("protobuf: varint longer than 10 bytes");
}

void write_varint(std::uint64_t value, std::string& out) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7f) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

std::string_view take(std::string_view in, size_t& pos, std::uint64_t n) {
  if (n > in.size() - pos) throw std::runtime_error("protobuf: field runs past the end of its message");
  const std::string_view out = in.substr(pos, n);
  pos += n;
  return out;
}

}  // namespace

std::vector<Field> parse(std::string_view message) {
  std::vector<Field> fields;
  size_t pos = 0;
  while (pos < message.size()) {
    const std::uint64_t key = read_varint(message, pos);
    Field f;
    f.number = static_cast<std::uint32_t>(key >> 3);
    f.type = static_cast<std::uint32_t>(key & 7);
    if (f.number == 0) throw std::runtime_error("protobuf: field number 0");
    switch (f.type) {
      case kVarint:
        f.varint = read_varint(message, pos);
        break;
      case kFixed64:
        f.bytes = take(message, pos, 8);
        break;
      case kLengthDelimited:
        f.bytes = take(message, pos, read_varint(message, pos));
        break;
      case kFixed32:
        f.bytes = take(message, pos, 4);
        break;
      default:
        throw std::runtime_error("protobuf: unsupported wire type " + std::to_string(f.type));
    }
    fields.push_back(std::move(f));
  }
  return fields;
}

std::string serialize(const std::vector<Field>& fields) {
  std::string out;
  for (const Field& f : fields) {
    write_varint(static_cast<std::uint64_t>(f.number) << 3 | f.type, out);
    if (f.type == kVarint) {
      write_varint(f.varint, out);
    } else {
      if (f.type == kLengthDelimited) write_varint(f.bytes.size(), out);
      out += f.bytes;
    }
  }
  return out;
}

Field varint_field(std::uint32_t number, std::uint64_t value) {
  Field f;
  f.number = number;
  f.type = kVarint;
  f.varint = value;
  return f;
}

Field bytes_field(std::uint32_t number, std::string bytes) {
  Field f;
  f.number = number;
  f.type = kLengthDelimited;
  f.bytes = std::move(bytes);
  return f;
}

std::vector<std::string> strings(const std::vector<Field>& fields, std::uint32_t number) {
  std::vector<std::string> out;
  for (const Field& f : fields)
    if (f.number == number && f.type == kLengthDelimited) out.push_back(f.bytes);
  return out;
}

std::vector<std::int64_t> varints(const std::vector<Field>& fields, std::uint32_t number) {
  std::vector<std::int64_t> out;
  for (const Field& f : fields) {
    if (f.number != number) continue;
    if (f.type == kVarint) {
      out.push_back(static_cast<std::int64_t>(f.varint));
    } else if (f.type == kLengthDelimited) {  // packed
      size_t pos = 0;
      while (pos < f.bytes.size()) out.push_back(static_cast<std::int64_t>(read_varint(f.bytes, pos)));
    }
  }
  return out;
}

}  // namespace wardmap::semantics::wire
