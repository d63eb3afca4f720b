#pragma once
// Splits grip's command line from the PETSc options that pass through to PETSc's own
// options database: everything after a lone `--` (for example `-- -ksp_type cg -pc_type gamg`).
#include <string>
#include <vector>

namespace grip {

struct SplitArguments {
  std::vector<std::string> grip;   // argv[0] and grip's own arguments, for CLI11
  std::vector<std::string> petsc;  // PETSc options, in order, without the `--`
};

SplitArguments split_petsc_arguments(int argc, const char* const* argv);

}  // namespace grip
