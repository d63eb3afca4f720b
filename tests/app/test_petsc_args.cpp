// PETSc options pass through after a lone `--`; everything before it is grip's.
#include <gtest/gtest.h>

#include "app/cli/petsc_args.hpp"

namespace grip {
namespace {

TEST(PetscArguments, EverythingAfterDoubleDashGoesToPetsc) {
  const char* argv[] = {"grip", "farm", "job.toml", "--", "-ksp_type", "cg", "-ksp_monitor"};
  const auto split = split_petsc_arguments(7, argv);
  EXPECT_EQ(split.grip, (std::vector<std::string>{"grip", "farm", "job.toml"}));
  EXPECT_EQ(split.petsc, (std::vector<std::string>{"-ksp_type", "cg", "-ksp_monitor"}));
}

TEST(PetscArguments, WithoutDoubleDashNothingGoesToPetsc) {
  const char* argv[] = {"grip", "-v", "farm", "-ksp_type"};
  const auto split = split_petsc_arguments(4, argv);
  EXPECT_EQ(split.grip.size(), 4u);
  EXPECT_TRUE(split.petsc.empty());
}

TEST(PetscArguments, OnlyTheFirstDoubleDashSplits) {
  const char* argv[] = {"grip", "--", "-a", "--", "-b"};
  const auto split = split_petsc_arguments(5, argv);
  EXPECT_EQ(split.grip, (std::vector<std::string>{"grip"}));
  EXPECT_EQ(split.petsc, (std::vector<std::string>{"-a", "--", "-b"}));
}

}  // namespace
}  // namespace grip
