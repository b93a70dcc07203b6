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

// Checked before a long run whose outputs are written at its end, so that a wrong --out is told
// at once rather than after the run it would lose. `option` names the flag in the message ("--out").
// Neither leaves anything (each makes and removes an empty folder in the nearest existing one, the
// only sure test of writing there). check_output_folder throws InputError(folder, ...) unless `folder` is a
// folder the process can write into or can make (its nearest existing ancestor is such a folder).
void check_output_folder(const std::filesystem::path& folder, const std::string& option);
// The same for a file written at the end: not a folder, in a folder that is or can be made writable.
void check_output_file(const std::filesystem::path& file, const std::string& option);

// Throws InputError(file, "timestamp ... is not after the previous one ...", line) on t <= previous.
void check_increasing(double t, double previous, const std::filesystem::path& file, long line);

}  // namespace wardmap::slam::io
