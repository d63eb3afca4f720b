#pragma once
// A bimanual-like Newton system source: a soft cube squeezed by two grippers' pairs of soft
// finger pads (one pair along x, one along y), each pad pinned to a kinematic jaw. The tet
// cell size sets the system's size, from about 2,000 DOFs (1 cm) up.
#include "solver/scene/scene.hpp"

namespace grip::bench {

// Pads start 1.1 mm from the cube, just beyond d_hat = 1 mm, and their jaws close at
// `closing_speed` (m/s) each, gravity off: at the default speed the contacts become active
// during the first step. (Pads placed inside d_hat make the first step's systems far harder.)
solver::SceneDescription bimanual_squeeze(double cell, double closing_speed = 0.03);

}  // namespace grip::bench
