#pragma once
// Whether an output file or folder can be written, checked on the command line before any work:
// what is wrong with it and the fix, or "" when it can be written.
#include <string>

namespace grip {

// A file to write: not a directory, writable if it exists, its folder there or creatable.
std::string output_file_problem(const std::string& path);

// A folder to write into: not a file, writable if it exists, else creatable.
std::string output_folder_problem(const std::string& path);

}  // namespace grip
