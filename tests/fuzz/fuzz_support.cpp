#include "tests/fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <typeinfo>

namespace wardmap::fuzz {

namespace fs = std::filesystem;

namespace {
fs::path folder_of_this_process() { return fs::temp_directory_path() / ("wardmap-fuzz-" + std::to_string(::getpid())); }
}  // namespace

fs::path scratch_folder() {
  static const fs::path dir = [] {
    const fs::path d = folder_of_this_process();
    fs::remove_all(d);
    fs::create_directories(d);
    std::atexit([] {  // libFuzzer's -max_total_time and the replay end through exit(); a crash keeps it
      std::error_code ec;
      fs::remove_all(folder_of_this_process(), ec);
    });
    return d;
  }();
  return dir;
}

fs::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const fs::path file = scratch_folder() / name;
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
  return file;
}

fs::path write_input(const std::string& name, const std::string& text) {
  return write_input(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void report_escape(const char* what, const char* kind, const std::exception* e) {
  std::fprintf(stderr, "fuzz: %s: %s escaped (%s), not an InputError naming the file: %s\n", what, kind,
               e ? typeid(*e).name() : "?", e ? e->what() : "");
  std::abort();
}

}  // namespace wardmap::fuzz
