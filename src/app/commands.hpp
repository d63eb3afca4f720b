#pragma once
// The work behind each `grip` subcommand, one function per subcommand, called by cli.cpp.
// Each returns the process exit code.
#include <string>
#include <vector>

namespace grip::commands {

}  // namespace grip::commands
