#include "src/synth/synthesis_settings.hpp"

#include <array>

namespace grip::synth {
namespace {

using config::Range;
using P = config::Parameter<SynthesisSettings>;

constexpr std::array kSynthesisParameters = {
    P{.key = "steps",
      .count = &SynthesisSettings::steps,
      .range = Range::at_least(1),
      .doc = "annealing steps per hand attempt (docs/synthesis.md)"},
    P{.key = "margin",
      .real = &SynthesisSettings::margin,
      .range = Range::at_least(0),
      .unit = "m",
      .doc = "clearance every candidate keeps beyond d_hat"},
};

}  // namespace

config::ParameterTable<SynthesisSettings> synthesis_parameter_table() {
  return kSynthesisParameters;
}

SynthesisParams synthesis_params(const SynthesisSettings& settings, double d_hat) {
  SynthesisParams params;
  params.antipodal.d_hat = params.hand.clearance.d_hat = d_hat;
  params.antipodal.margin = params.hand.clearance.margin = settings.margin;
  params.hand.steps = settings.steps;
  params.bimanual.hand_clearance = d_hat + settings.margin;
  return params;
}

}  // namespace grip::synth
