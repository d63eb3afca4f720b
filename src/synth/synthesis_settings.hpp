#pragma once
// The synthesis settings a user gives (a job file's [synthesis] table, grip synth's options) as
// one parameter table, and the synthesizers' parameters they make with the barrier's d_hat.
#include "src/config/parameter.hpp"
#include "src/synth/synthesize.hpp"

namespace grip::synth {

struct SynthesisSettings {
  int steps = 1500;      // annealing steps per hand attempt
  double margin = 5e-4;  // m, clearance every candidate keeps beyond d_hat
};

config::ParameterTable<SynthesisSettings> synthesis_parameter_table();

// Every candidate kept d_hat + margin clear of the object, by either synthesizer and by a
// bimanual pair's two hands.
SynthesisParams synthesis_params(const SynthesisSettings& settings, double d_hat);

}  // namespace grip::synth
