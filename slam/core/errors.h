// Errors at the edges (files, settings, models): one line that names the file, the line where there
// is one, and the problem. The CLI turns them into exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace wardmap {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem, long line = 0)
      : std::runtime_error(format(file, problem, line)), file_(file), line_(line) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }

 private:
  static std::string format(const std::string& file, const std::string& problem, long line) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    return s + ": " + problem;
  }
  std::string file_;
  long line_;
};

}  // namespace wardmap
