// Shared by the fuzz targets of tests/fuzz (docs/DEVELOPMENT.md#fuzzing): the readers take paths, so a
// target writes the fuzzer's bytes to a file of its own process; and a reader's only way to refuse
// an input is an InputError naming the file (wire::parse's std::runtime_error for the ONNX rewrites),
// so any other exception is reported as a finding, with its type, and aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>

#include "slam/core/errors.h"

namespace wardmap::fuzz {

// A folder of this process under the system's temporary folder, emptied on the first call and
// removed when the process exits normally.
std::filesystem::path scratch_folder();

// Writes `size` bytes to scratch_folder() / name and returns the path.
std::filesystem::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size);
std::filesystem::path write_input(const std::string& name, const std::string& text);

// Prints "<target>: <what> escaped as <kind>, not as an InputError: <message>" and aborts.
[[noreturn]] void report_escape(const char* what, const char* kind, const std::exception* e);

// Runs read(); an InputError is an accepted refusal, anything else a finding.
template <typename Read>
void refuses_only_with_input_error(const char* what, Read read) {
  try {
    read();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    report_escape(what, "a std::exception", &e);
  } catch (...) {
    report_escape(what, "a non-std exception", nullptr);
  }
}

}  // namespace wardmap::fuzz
