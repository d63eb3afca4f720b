#pragma once
// Antipodal grasp sampling for two-finger parallel grippers in the spirit of GPD: a surface
// point and its local frame, rotations about the curvature axis, approach deepening until the
// gripper would collide, centring on the object points between the fingers, a friction-cone
// antipodality test, and an exact clearance test of the posed fingers.
#include <cstdint>

#include "src/grippers/gripper_registry.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/synth/attempt_driver.hpp"
#include "src/synth/prepared_object.hpp"

namespace grip::synth {

struct AntipodalParams {
  int cloud_points = 4000;      // object surface samples for frames and quick collision tests
  double frame_radius = 0.01;   // m, neighbourhood of a local frame
  int rotations = 8;            // approach directions per point, over [-90, 90) deg about the
                                // curvature axis
  double depth_step = 0.004;    // m, approach deepening step
  double min_inset = 0.01;      // m, the surface point stays at least this far from the mount
  double body_depth = 0.04;     // m, the jaw carriage behind the finger mounts (collision box)
  double friction = 0.5;        // friction coefficient of the antipodality cone
  double contact_band = 0.003;  // m, points this close to a jaw-side extreme can be contacts
  double gap = 0.004;           // m, jaw opening beyond the object's width, per side
  double d_hat = 1e-3;          // m, the IPC barrier's activation distance
  double margin = 5e-4;         // m, clearance beyond d_hat every candidate keeps
  std::int64_t max_attempts_per_candidate = 200;
  int block = 256;  // attempts per parallel block
};

// Energy terms of a parallel-gripper candidate (Candidate::energies, in this order):
// antipodal_angle (rad, the larger angle between a contact normal and the closing axis),
// depth (m, deepening reached), width (m, object width between the contacts' jaw sides).
//
// `kind` names a parallel gripper (not a hand) and `gripper` is its model. Every returned
// candidate has opening in the gripper's range and exact clearance >= d_hat + margin.
SynthesisResult sample_antipodal_grasps(const PreparedObject& object,
                                        const grippers::ParallelGripper& gripper,
                                        grippers::GripperKind kind, const AntipodalParams& params,
                                        std::uint64_t seed, int count);

// The posed surface of a parallel-gripper hand (both fingers at the hand's opening), world frame.
geometry::SurfaceMesh posed_parallel_surface(const grippers::ParallelGripper& gripper,
                                             const HandGrasp& hand);

}  // namespace grip::synth
