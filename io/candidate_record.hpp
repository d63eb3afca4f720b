#pragma once
// The outcome of one grasp candidate: one row of the dataset's candidate table. Sizes per
// hand follow the candidate's gripper record (hands, joints, fingers).
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace grip::io {

enum class Status : std::uint8_t {
  kPending = 0,  // not simulated yet (the table's fill value)
  kSuccess = 1,
  kFailure = 2,
};

enum class FailureKind : std::uint8_t {
  kNone = 0,
  kInitialPenetration = 1,  // the synthesized pose intersects the object; not simulated
  kNoContact = 2,           // the closed gripper never touched the object
  kLostContact = 3,         // the object left the gripper during the gravity test
  kDisplaced = 4,           // still held, but the centre of mass moved past the threshold
  kNewtonLimit = 5,         // Newton did not converge within the iteration limit
  kNumerical = 6,           // non-finite state or a failed factorization
  kUnsettled = 7,           // the closed grasp never came to a steady state; not tested
};
inline constexpr std::uint8_t kFailureKindCount = 8;

std::string_view to_string(Status status);
std::string_view to_string(FailureKind kind);

struct NewtonStatistics {
  std::uint32_t steps = 0;           // accepted time steps
  std::uint32_t iterations = 0;      // Newton iterations over all steps
  std::uint32_t max_iterations = 0;  // most Newton iterations in one step
  std::uint32_t retries = 0;         // failed steps (or parts) retried as two half steps

  bool operator==(const NewtonStatistics&) const = default;
};

struct CandidateRecord {
  std::uint64_t id = 0;            // the candidate's row, fixed by the plan
  std::vector<double> hand_poses;  // 12 per hand: row-major 3x4 [R | t], world from hand, m
  std::vector<double> joints;      // joint_names.size() per hand, at the synthesized pose
  Status status = Status::kPending;
  FailureKind failure = FailureKind::kNone;
  double d1 = 0;  // m, penetration depth (paper Eq. D1)
  double d2 = 0;  // m, absolute gripper-object distance (paper Eq. D2)
  // m, how far the object slipped in the gripper by the end of each gravity phase: +x, -x, +y,
  // -y, +z, -z.
  std::array<double, 6> displacement{};
  // s, how long each gravity phase ran: phase_duration plus the wait for the object to come to
  // rest; the verdict's threshold grows with the time under gravity (TrialParameters).
  std::array<double, 6> phase_seconds{};
  std::vector<double> closing_forces;  // N, per finger per hand, when the squeeze settled
  double contact_friction = 0;         // mu of the finger-object contact pairs
  NewtonStatistics newton;
  // How many of the trajectory's frames (closing, then validation) hold states the trial
  // reached; those after repeat the last of them. A trial stops once its verdict is decided
  // (a gravity phase's end found the object dropped or slipped), or when it fails earlier.
  std::uint32_t simulated_frames = 0;
  double wall_time = 0;  // s; the one column that differs between otherwise equal runs

  bool operator==(const CandidateRecord&) const = default;
};

// Per-frame state of one trajectory (closing frames, then validation frames). n is the
// object's vertex count, g = hands x the gripper's vertex count, J its joints per hand.
struct TrajectoryRecord {
  std::vector<float> object_vertices;   // frames x n x 3, m
  std::vector<float> gripper_vertices;  // frames x g x 3, m
  std::vector<float> contact_forces;    // frames x n x 3, N, normal contact force per vertex
  std::vector<float> friction_forces;   // frames x n x 3, N, friction force per vertex
  // frames x g x 3, N: the same forces on each gripper surface vertex (its side of the pairs)
  std::vector<float> gripper_contact_forces;
  std::vector<float> gripper_friction_forces;
  std::vector<double> object_poses;  // frames x 12, row-major 3x4 [A | t] of the object
  std::vector<double> hand_poses;    // frames x hands x 12
  std::vector<double> joints;        // frames x hands x J

  bool operator==(const TrajectoryRecord&) const = default;
};

// What a worker hands the writer for one candidate. The trajectory and stresses are stored
// only where the plan gave the candidate a slot for them.
struct CandidateResult {
  CandidateRecord record;
  std::optional<TrajectoryRecord> trajectory;
  std::optional<std::vector<float>> stress;  // Pa, von Mises per object tet, settled grasp
  // Pa, von Mises per tet of the gripper's soft fingers (GripperRecord::tets), settled grasp
  std::optional<std::vector<float>> finger_stress;
};

}  // namespace grip::io
