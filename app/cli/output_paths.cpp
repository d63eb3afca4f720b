#include "app/cli/output_paths.hpp"

#include <unistd.h>

#include <filesystem>
#include <system_error>

namespace grip {
namespace {

namespace fs = std::filesystem;

// Built by appending: "'" + string + "'" draws a false -Wrestrict warning from GCC 12.
std::string quoted(const fs::path& path) {
  std::string text = "'";
  text += path.string();
  text += '\'';
  return text;
}

// `folder` exists and may be written into, or can be created: its nearest existing ancestor is
// a writable folder. Nothing is created.
std::string folder_problem(const fs::path& folder) {
  fs::path existing = folder.empty() ? fs::path(".") : folder;
  std::error_code error;
  fs::file_status status = fs::status(existing, error);
  while (!fs::exists(status)) {
    if (status.type() != fs::file_type::not_found) {  // not missing but unreadable
      return "cannot reach " + quoted(existing) + " (" + error.message() + "); choose another path";
    }
    existing = existing.has_relative_path() && existing.has_parent_path() ? existing.parent_path()
               : existing.is_absolute()                                   ? existing.root_path()
                                                                          : fs::path(".");
    status = fs::status(existing, error);
  }
  if (!fs::is_directory(status)) {
    return existing == folder ? quoted(folder) + " is a file, not a folder; choose another path"
                              : quoted(existing) + " is a file, so folder " + quoted(folder) +
                                    " cannot be created; choose another path";
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    return "folder " + quoted(existing) +
           " is not writable; choose another path or make the folder writable";
  }
  return "";
}

}  // namespace

std::string output_file_problem(const std::string& path) {
  if (path.empty()) return "the path is empty; give a file path";
  const fs::path file(path);
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (fs::is_directory(status)) {
    return quoted(file) + " is a directory; give a file path (such as " +
           quoted(file / "out.json") + ")";
  }
  if (fs::exists(status) && ::access(file.c_str(), W_OK) != 0) {
    return quoted(file) + " is not writable; choose another path or make the file writable";
  }
  return folder_problem(file.parent_path());
}

std::string output_folder_problem(const std::string& path) {
  if (path.empty()) return "the path is empty; give a folder";
  const fs::path folder(path);
  std::error_code error;
  const fs::file_status status = fs::status(folder, error);
  if (fs::exists(status) && !fs::is_directory(status)) {
    return quoted(folder) + " is a file, not a folder; give a folder";
  }
  return folder_problem(folder);
}

}  // namespace grip
