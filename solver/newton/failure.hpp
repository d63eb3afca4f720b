#pragma once
// Why an environment failed, as a code: callers decide on the code, never on the wording of the
// message that comes with it (Environment::failure()).
namespace grip::solver {

enum class Failure {
  kNone,
  kIntersectingStart,  // two surfaces touch or cross before the first step
  kNewtonLimit,        // Newton did not converge within max_newton_iters, after every retry
  kNonFinite,          // a non-finite gradient or Newton step
  kLinearSolve,        // the Newton system could not be factorized or solved
  kCcdNoMotion,        // continuous collision detection allowed no motion at all
  kInversion,          // no step length keeps every tetrahedron positively oriented
  kLineSearch,         // the line search could not decrease the incremental potential
};

}  // namespace grip::solver
