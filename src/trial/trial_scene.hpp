#pragma once
// What every trial scene is to the protocol, whichever gripper it holds: the static part shared
// by every trial of one object and one gripper (or two, bimanual), built once: its solver Model,
// the protocol's settings, the dataset's record of the gripper, and the protocol's view of it
// with candidates placed (TrialGripper). A parallel gripper's scene (ParallelTrialScene) and a
// hand's (HandTrialScene) implement it; src/trial/trial.hpp builds one from a gripper's registry
// row and runs candidates through it.
#include <memory>
#include <string>
#include <vector>

#include "io/gripper_record.hpp"
#include "solver/model/model.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::trial {

class TrialGripper;

// A vertex of one of the model's bodies: the body, and the vertex's index among its vertices
// (BodySubsystem::vertex_count).
struct BodyVertex {
  int body = -1;
  int vertex = -1;
};

class TrialScene {
 public:
  virtual ~TrialScene() = default;

  virtual const std::shared_ptr<const solver::Model>& model() const = 0;
  virtual const TrialParameters& parameters() const = 0;
  // The grippers a candidate places: 1, or 2 for a bimanual trial.
  virtual int gripper_count() const = 0;
  // The dataset's description of the gripper(s): what the joints and closing forces mean, and
  // the surface at rest in the vertex order of the recorded frames.
  virtual io::GripperRecord gripper_record() const = 0;
  // The gripper's model for a log line: a soft finger's mesh (per finger), or a hand's fingers.
  virtual std::string description() const = 0;
  // The protocol's view of this scene with `candidates` (each of gripper_count() hands, in the
  // scene's gripper order: the right hand first). Throws std::out_of_range naming a candidate
  // the gripper cannot take.
  virtual std::unique_ptr<TrialGripper> protocol_gripper(
      const std::vector<synth::Candidate>& candidates) const = 0;
};

}  // namespace grip::trial
