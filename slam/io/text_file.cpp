#include "slam/io/text_file.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include "slam/core/errors.h"

namespace wardmap::slam::io {

namespace fs = std::filesystem;

void for_each_data_line(const fs::path& file, bool csv,
                        const std::function<void(long, const std::vector<std::string>&)>& fn) {
  if (!fs::exists(file)) throw InputError(file.string(), "file not found");
  if (fs::is_directory(file)) throw InputError(file.string(), "is a folder, not a text file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open: " + std::generic_category().message(errno));
  std::string line;
  long number = 0;
  std::vector<std::string> tokens;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    tokens.clear();
    std::string tok;
    for (char c : line.substr(first)) {
      if (c == ' ' || c == '\t' || (csv && c == ',')) {
        if (!tok.empty()) tokens.push_back(tok);
        tok.clear();
      } else {
        tok.push_back(c);
      }
    }
    if (!tok.empty()) tokens.push_back(tok);
    fn(number, tokens);
  }
  if (in.bad()) throw InputError(file.string(), "read error", number);
}

double parse_double(const std::string& token, const fs::path& file, long line, const char* what) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(token.c_str(), &end);
  if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE || !std::isfinite(v))
    throw InputError(file.string(), std::string(what) + ": '" + token + "' is not a number", line);
  return v;
}

long long parse_int(const std::string& token, const fs::path& file, long line, const char* what) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(token.c_str(), &end, 10);
  if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE)
    throw InputError(file.string(), std::string(what) + ": '" + token + "' is not an integer", line);
  return v;
}

void write_file_atomic(const fs::path& file, const std::string& contents) {
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  const fs::path tmp = file.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(file.string(), "cannot write: " + std::generic_category().message(errno));
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw InputError(file.string(), "write failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    const std::string problem = ec.message();  // before the removal resets it
    fs::remove(tmp, ec);
    throw InputError(file.string(), "cannot rename the temporary file into place: " + problem);
  }
}

namespace {

// Throws InputError(path, ...) unless `existing`, the nearest existing one of `path` and its
// ancestors, is a folder the process can write into (where `path` is, or would be made).
void check_writable_from(const fs::path& path, fs::path existing, const std::string& option) {
  std::error_code ec;
  while (!existing.empty() && !fs::exists(existing, ec)) existing = existing.parent_path();
  if (existing.empty()) existing = ".";
  if (!fs::is_directory(existing, ec)) {
    if (existing == path) throw InputError(path.string(), option + " names a file; it must be a folder (new or existing)");
    throw InputError(path.string(), option + ": cannot be made: '" + existing.string() + "' is a file");
  }
  // Made and removed at once: access() would answer yes to root for every folder, and to anyone on
  // NFS with root squashing or on pseudo file systems such as /proc.
  std::string probe = (existing / ".wardmap-write-check-XXXXXX").string();
  if (::mkdtemp(probe.data()) == nullptr)
    throw InputError(path.string(), option + ": cannot write into '" + existing.string() +
                                        "': " + std::generic_category().message(errno));
  ::rmdir(probe.c_str());
}

}  // namespace

void check_output_folder(const fs::path& folder, const std::string& option) {
  check_writable_from(folder, folder, option);
}

void check_output_file(const fs::path& file, const std::string& option) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw InputError(file.string(), option + " names a folder; it must be a file");
  check_writable_from(file, file.parent_path(), option);
}

// The shortest decimal form that reads back as the same double (what the file most likely said).
static std::string shortest(double v) {
  char buf[40];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

void check_increasing(double t, double previous, const fs::path& file, long line) {
  if (t <= previous) {
    std::ostringstream s;
    s << "timestamp " << shortest(t) << " is not after the previous one " << shortest(previous)
      << " (timestamps must increase)";
    throw InputError(file.string(), s.str(), line);
  }
}

}  // namespace wardmap::slam::io
