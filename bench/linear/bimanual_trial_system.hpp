#pragma once
// Newton systems from a real bimanual soft trial: two production fin-ray grippers pinch a soft
// 40 x 5 x 4 cm bar (jobs/bimanual-fin-ray.toml's soft bar) near its ends, run by the trial
// protocol itself; the system is taken at the first Newton iteration in which the fingers'
// contacts couple them to the bar, and the trial is then abandoned.
#include "bench/linear/newton_system.hpp"

namespace grip::bench {

// The bar is a structured tet grid of cell `cell` (m), so its size is set without meshing
// cost: about 0.5 million DOFs at 1.7 mm. Throws std::runtime_error if the trial ends or fails
// before its fingers touch the bar.
NewtonSystem capture_bimanual_trial_system(double cell);

}  // namespace grip::bench
