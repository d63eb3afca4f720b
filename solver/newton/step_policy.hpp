#pragma once
// How an environment's steps may depart from the defaults, only to measure what a default saves
// (bench/model): set for a whole batch (Batch::set_policy) or for one environment.
namespace grip::solver {

struct StepPolicy {
  // On (the default), a step whose Newton converged is finished at once, and in a batch the
  // environment is frozen while others iterate. Off, a converged step is held open, the way one
  // global convergence test of a monolithic solver keeps every part iterating until the slowest
  // converges: each further iteration takes one more Newton step from there, with no iteration
  // limit (the slowest environment's bounds it) and no Armijo halving for its own energy (in a
  // monolithic solve that energy is one term of a sum whose decrease decides).
  bool freeze_converged = true;
  // Off (the default), contact pairs with mu = 0 get no friction terms. On, they get them anyway
  // (each adds zero force at the full cost of its lag and its derivatives).
  bool friction_terms_at_zero_mu = false;
};

}  // namespace grip::solver
