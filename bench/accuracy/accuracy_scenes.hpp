#pragma once
// The standard trial scenes of `grip bench accuracy` (fin-ray x rigid, fin-ray x soft, hand x
// rigid), each a few candidates run through the real protocol under reduced settings that keep
// a sweep of the solver's settings affordable. There is no bimanual trial scene in the code.
#include <functional>
#include <string>
#include <vector>

#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

// One run of a scene's candidates: their outcomes and the wall and CPU time of the trials alone
// (the scene's construction left out).
struct SceneRun {
  std::vector<trial::TrialOutcome> outcomes;
  double seconds = 0;
  // The process's CPU time over all its threads: on a shared machine it moves far less with
  // other processes' load than the wall time does.
  double cpu_seconds = 0;
};

struct AccuracyScene {
  std::string name;                   // "fin-ray x rigid"
  std::string setup;                  // object, candidates and reductions, in words
  trial::TrialParameters parameters;  // the scene's protocol: the sweeps vary around it
  std::string mesh_setting;           // what the mesh sweep varies, e.g. "fin-ray layers"
  std::vector<double> mesh_values;    // coarse to fine, the default among them; empty: no sweep
  double default_mesh = 0;
  // Builds the scene at `mesh` with `parameters` and runs every candidate on `threads`
  // threads (0: all cores).
  std::function<SceneRun(const trial::TrialParameters& parameters, double mesh, int threads)> run;
};

// The scene names standard_scenes() knows, in order.
std::vector<std::string> standard_scene_names();

// The named scenes, in the order given. Throws std::invalid_argument for an unknown name (and
// for "bimanual", saying that no bimanual trial scene exists).
std::vector<AccuracyScene> standard_scenes(const std::vector<std::string>& names);

}  // namespace grip::bench
