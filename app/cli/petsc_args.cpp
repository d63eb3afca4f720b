#include "app/cli/petsc_args.hpp"

#include <string_view>

namespace grip {

SplitArguments split_petsc_arguments(int argc, const char* const* argv) {
  SplitArguments split;
  int i = 0;
  for (; i < argc; ++i) {
    if (i > 0 && std::string_view(argv[i]) == "--") break;
    split.grip.emplace_back(argv[i]);
  }
  for (++i; i < argc; ++i) split.petsc.emplace_back(argv[i]);
  return split;
}

}  // namespace grip
