#pragma once
// One case of `grip bench hard`: a scene built in code that pushes the solver where IPC's
// guarantees are hardest to keep, how many steps to run it, and what else must hold physically.
#include <functional>
#include <string>
#include <vector>

#include "solver/environment.hpp"
#include "solver/scene/scene.hpp"

namespace grip::bench {

// A case-specific physical check, called after every accepted step (`last` on the final one):
// empty when it holds, else what broke.
using PhysicalCheck = std::function<std::string(const solver::Environment& env, bool last)>;

struct HardCase {
  std::string name;
  std::string challenge;  // what makes it hard, in one line
  solver::SceneDescription scene;
  int steps = 0;
  // The solver failing with a reason is this case's right outcome (the scene asks for the
  // impossible); otherwise a solver failure fails the case.
  bool failure_expected = false;
  PhysicalCheck check;  // may be empty
};

// The suite, in a fixed order.
std::vector<HardCase> hard_cases();

}  // namespace grip::bench
