// Line-oriented reading of the dataset text files, with the file and line in every error, and
// writing of outputs through a temporary name so that no half-written file is ever left behind.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace wardmap::slam::io {

// Calls fn(line_number, tokens) for every non-empty line that does not start with '#'. Tokens are
// split on spaces, tabs and (when csv is true) commas. Throws InputError when the file can't be read.
void for_each_data_line(const std::filesystem::path& file, bool csv,
                        const std::function<void(long, const std::vector<std::string>&)>& fn);

// Parses a number, or throws InputError(file, "<what>: '<token>' is not a number", line).
double parse_double(const std::string& token, const std::filesystem::path& file, long line, const char* what);
long long parse_int(const std::string& token, const std::filesystem::path& file, long line, const char* what);

// Writes contents to `file` through `file.tmp.<pid>` and a rename; creates parent folders.
void write_file_atomic(const std::filesystem::path& file, const std::string& contents);

// Throws InputError(file, "timestamp ... is not after the previous one ...", line) on t <= previous.
void check_increasing(double t, double previous, const std::filesystem::path& file, long line);

}  // namespace wardmap::slam::io
