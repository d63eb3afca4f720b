#pragma once
// A real Newton system taken from a running environment, through the solver's
// LinearSystemSolver hook: the matrix and right-hand side of its last Newton iteration.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/scene/scene.hpp"

namespace grip::bench {

struct NewtonSystem {
  Eigen::SparseMatrix<double> lower;  // lower triangle, column-major, compressed
  Eigen::VectorXd rhs;
  int newton_iterations = 0;  // over the steps taken to get here
};

// Steps an environment of `scene` `steps` times, every system solved by CHOLMOD, and returns
// the last system it solved. Throws std::runtime_error when the environment fails.
NewtonSystem capture_newton_system(const solver::SceneDescription& scene, int steps);

}  // namespace grip::bench
