#include "tests/io/synthetic_dataset.hpp"

#include <random>

namespace grip::io::testing {

namespace {

ObjectRecord box(const std::string& name, bool soft, double size) {
  ObjectRecord object;
  object.name = name;
  object.category = soft ? "sponge" : "box";
  object.scale = size;
  object.soft = soft;
  object.material = {soft ? 1e5 : 1e9, 0.4, 1000.0, 0.8};
  for (int i = 0; i < 8; ++i) {
    object.vertices.insert(object.vertices.end(),
                           {size * (i & 1), size * ((i >> 1) & 1), size * ((i >> 2) & 1)});
  }
  object.triangles = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                      2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  if (soft) object.tets = {0, 1, 3, 7, 0, 1, 7, 5, 0, 5, 7, 4, 0, 3, 2, 7, 0, 2, 6, 7, 0, 6, 4, 7};
  return object;
}

GripperRecord gripper(const std::string& name, std::uint32_t hands, std::uint32_t joints,
                      std::uint32_t fingers, std::uint32_t vertices) {
  GripperRecord g;
  g.name = name;
  g.kind = hands == 1 ? "parallel" : "hand";
  g.soft = hands == 1;
  g.hands = hands;
  for (std::uint32_t j = 0; j < joints; ++j) g.joint_names.push_back("joint_" + std::to_string(j));
  for (std::uint32_t f = 0; f < fingers; ++f)
    g.finger_names.push_back("finger_" + std::to_string(f));
  for (std::uint32_t v = 0; v < hands * vertices; ++v) {
    g.vertices.insert(g.vertices.end(), {0.01 * v, 0.02 * v, 0.03});
  }
  for (std::uint32_t h = 0; h < hands; ++h) {
    const auto first = static_cast<std::int32_t>(h * vertices);
    g.triangles.insert(g.triangles.end(), {first, first + 1, first + 2});
  }
  if (g.soft) {  // two soft fingers of one tet each
    g.tet_vertices = g.vertices;
    g.tets = {0, 1, 2, 3, 2, 3, 4, 5};
  }
  return g;
}

// Uniform in [lo, hi) from the generator's raw bits, identical on every platform.
double uniform(std::mt19937_64& random, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(random() >> 11) * 0x1.0p-53;
}

template <typename T>
std::vector<T> values(std::mt19937_64& random, std::size_t count, double lo, double hi) {
  std::vector<T> out(count);
  for (auto& value : out) value = static_cast<T>(uniform(random, lo, hi));
  return out;
}

}  // namespace

DatasetPlan synthetic_plan(std::uint32_t candidates) {
  DatasetPlan plan;
  plan.objects = {box("cube", false, 0.05), box("soft_cube", true, 0.04),
                  box("big_box", false, 0.2)};
  plan.grippers = {gripper("umi", 1, 1, 2, 6), gripper("leap_bimanual", 2, 3, 4, 7)};
  plan.closing_frames = 3;
  plan.validation_frames = 4;
  for (std::uint32_t id = 0; id < candidates; ++id) {
    CandidateSlot slot;
    slot.object = id % 3;
    slot.gripper = (id / 3) % 2;
    slot.frames = id % 4 != 1;
    slot.stress = slot.object == 1 && id % 5 != 0;
    slot.finger_stress = slot.gripper == 0 && id % 2 == 0;
    plan.candidates.push_back(slot);
  }
  return plan;
}

Provenance synthetic_provenance(const std::string& job_text, std::uint64_t seed) {
  Provenance provenance;
  provenance.job_file = "jobs/synthetic.toml";
  provenance.job_text = job_text;
  provenance.seed = seed;
  provenance.grip_version = "0.1.0";
  provenance.git_revision = "abcdef123456";
  provenance.parameters = {{"physics.dt", "0.01"}, {"physics.kappa", "3e6"}, {"trial.frames", "7"}};
  return provenance;
}

CandidateResult synthetic_result(const DatasetLayout& layout, std::uint64_t id,
                                 std::uint64_t seed) {
  std::mt19937_64 random(seed * 1000003u + id);
  const DatasetLayout::Gripper& g = layout.grippers[layout.gripper[id]];
  const DatasetLayout::Object& o = layout.objects[layout.object[id]];
  CandidateResult result;
  CandidateRecord& r = result.record;
  r.id = id;
  r.hand_poses = values<double>(random, 12u * g.hands, -1, 1);
  r.joints = values<double>(random, std::size_t{g.joints} * g.hands, -1.5, 1.5);
  const bool success = random() % 3 != 0;
  r.status = success ? Status::kSuccess : Status::kFailure;
  r.failure = success ? FailureKind::kNone
                      : static_cast<FailureKind>(1 + random() % (kFailureKindCount - 1));
  r.d1 = success ? 0.0 : uniform(random, 0, 1e-3);
  r.d2 = uniform(random, 0, 2e-3);
  for (double& d : r.displacement) d = uniform(random, 0, 1e-4);
  r.closing_forces = values<double>(random, std::size_t{g.fingers} * g.hands, 0, 50);
  r.newton = {static_cast<std::uint32_t>(100 + random() % 10),
              static_cast<std::uint32_t>(300 + random() % 100),
              static_cast<std::uint32_t>(5 + random() % 20)};
  r.wall_time = uniform(random, 0.1, 3.0);
  const std::size_t frames = layout.frames();
  r.simulated_frames = static_cast<std::uint32_t>(random() % (frames + 1));
  if (layout.frame_slot[id] >= 0) {
    TrajectoryRecord t;
    t.object_vertices = values<float>(random, frames * o.vertices * 3, -0.1, 0.1);
    t.gripper_vertices = values<float>(random, frames * g.hands * g.vertices * 3, -0.1, 0.1);
    t.contact_forces = values<float>(random, frames * o.vertices * 3, -5, 5);
    t.friction_forces = values<float>(random, frames * o.vertices * 3, -5, 5);
    t.object_poses = values<double>(random, frames * 12, -1, 1);
    t.hand_poses = values<double>(random, frames * g.hands * 12, -1, 1);
    t.joints = values<double>(random, frames * g.hands * g.joints, -1.5, 1.5);
    t.gripper_contact_forces = values<float>(random, frames * g.hands * g.vertices * 3, -5, 5);
    t.gripper_friction_forces = values<float>(random, frames * g.hands * g.vertices * 3, -5, 5);
    result.trajectory = std::move(t);
  }
  if (layout.stress_slot[id] >= 0) result.stress = values<float>(random, o.tets, 0, 1e6);
  if (layout.finger_stress_slot[id] >= 0) {
    result.finger_stress = values<float>(random, g.tets, 0, 1e6);
  }
  return result;
}

}  // namespace grip::io::testing
