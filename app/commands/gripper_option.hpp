#pragma once
// The --gripper value of grip synth and grip trial: a built-in gripper's name or a gripper
// description file (docs/assets.md, "Your own soft gripper").
#include <filesystem>
#include <string>

#include "app/cli/command_line.hpp"
#include "src/grippers/gripper_description.hpp"
#include "src/grippers/gripper_registry.hpp"

namespace grip::commands {

inline std::string gripper_option_help() {
  return "Gripper: " + grippers::gripper_name_list() +
         ", or a soft gripper's description file (*.toml; docs/assets.md)";
}

inline cli::Check gripper_check() {
  return cli::Check::custom(
      [](const std::string& value) -> std::string {
        if (grippers::find_gripper_type(value)) return "";
        if (grippers::is_gripper_description(value)) {
          if (std::filesystem::is_regular_file(value)) return "";
          return "names the description file '" + value + "', which does not exist";
        }
        return "must be " + grippers::gripper_name_list() +
               " or a gripper description file (*.toml), not '" + value + "'";
      },
      "GRIPPER");
}

}  // namespace grip::commands
