// Errors at the edges (files, settings, models): one line that names the file, the line where there
// is one, and the problem. The CLI turns them into exit code 2.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace wardmap {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem, long line = 0)
      : std::runtime_error(format(file, problem, line)), file_(file), problem_(problem), line_(line) {}
  const std::string& file() const { return file_; }
  const std::string& problem() const { return problem_; }
  long line() const { return line_; }

 private:
  static std::string format(const std::string& file, const std::string& problem, long line) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    return s + ": " + problem;
  }
  std::string file_;
  std::string problem_;
  long line_;
};

// One frame of an opened sequence that cannot be read: its file does not decode (a recording cut
// short, a disk error) or is unlike the sequence's first frame. A run skips it as a dropped frame;
// any other InputError stops the run.
class FrameReadError : public InputError {
 public:
  FrameReadError(const InputError& cause, size_t frame)
      : InputError(cause.file(), cause.problem(), cause.line()), frame_(frame) {}
  size_t frame() const { return frame_; }

 private:
  size_t frame_;
};

}  // namespace wardmap
