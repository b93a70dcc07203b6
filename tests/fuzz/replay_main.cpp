// main() of a fuzz target in an ordinary build: runs LLVMFuzzerTestOneInput on every file given, or
// every file in the folders given (the committed corpus: seeds and the inputs of fixed findings), so
// that ctest keeps them passing without libFuzzer. A finding aborts, as under the fuzzer. Inputs
// that do not exist are left out; with none at all it exits 77, which ctest counts as skipped.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    if (fs::is_directory(argv[i])) {
      for (const auto& e : fs::recursive_directory_iterator(argv[i]))
        if (e.is_regular_file()) files.push_back(e.path());
    } else if (fs::is_regular_file(argv[i])) {
      files.emplace_back(argv[i]);
    } else {  // a seed of ../shared (the ONNX models) where it is absent
      std::printf("%s: not found, left out\n", argv[i]);
    }
  }
  if (files.empty()) {
    std::printf("skipped: none of the inputs given exists (../shared absent?)\n");
    return 77;  // ctest's SKIP_RETURN_CODE
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%zu inputs replayed, none escaped or crashed\n", files.size());
  return 0;
}
