// How each kind of trial scene describes its gripper: the dataset's record (io::GripperRecord:
// what its joints and closing forces mean, its surface at rest in the vertex order of the
// recorded frames) and a line for the log.
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"

#include <stdexcept>
#include <string>

namespace grip::trial {

namespace {

// Appends one hand's surface (row-major, as the meshes store it) after the hands before it.
void add_surface(io::GripperRecord& record, const geometry::SurfaceMesh& surface) {
  const auto offset = static_cast<std::int32_t>(record.vertex_count());
  record.vertices.insert(record.vertices.end(), surface.vertices.data(),
                         surface.vertices.data() + surface.vertices.size());
  for (Eigen::Index i = 0; i < surface.triangles.size(); ++i) {
    record.triangles.push_back(surface.triangles.data()[i] + offset);
  }
}

// Appends one hand's soft fingers (empty when rigid) after the hands before it.
void add_tets(io::GripperRecord& record, const geometry::TetMesh& fingers) {
  const auto offset = static_cast<std::int32_t>(record.tet_vertices.size() / 3);
  for (Eigen::Index v = 0; v < fingers.vertices.rows(); ++v) {
    for (int k = 0; k < 3; ++k) record.tet_vertices.push_back(fingers.vertices(v, k));
  }
  for (Eigen::Index t = 0; t < fingers.tets.rows(); ++t) {
    for (int k = 0; k < 4; ++k) record.tets.push_back(fingers.tets(t, k) + offset);
  }
}

// A bimanual setting is its own gripper record, named apart from the one-gripper setting.
std::string setting_name(const std::string& name, int hands) {
  return hands == 2 ? name + "-bimanual" : name;
}

}  // namespace

io::GripperRecord ParallelTrialScene::gripper_record() const {
  const grippers::ParallelGripper& gripper = gripper_;
  io::GripperRecord record;
  record.name = setting_name(gripper.name, gripper_count());
  record.kind = "parallel";
  record.hands = static_cast<std::uint32_t>(gripper_count());
  record.soft = gripper.soft_finger.has_value();
  record.joint_names = {"opening"};
  record.finger_names = {"positive", "negative"};
  const geometry::SurfaceMesh surface = gripper.surface(gripper.max_opening);
  const geometry::TetMesh fingers = gripper.finger_tets(gripper.max_opening);
  for (int g = 0; g < gripper_count(); ++g) {
    add_surface(record, surface);
    add_tets(record, fingers);
  }
  return record;
}

std::string ParallelTrialScene::description() const {
  if (!gripper_.soft_finger) return "rigid fingers";
  const geometry::TetMesh& finger = gripper_.soft_finger->mesh;
  return std::to_string(finger.vertices.rows()) + " vertices, " +
         std::to_string(finger.tets.rows()) + " tets";
}

std::string HandTrialScene::description() const {
  return std::to_string(fingers_.size()) + " fingers";
}

io::GripperRecord HandTrialScene::gripper_record() const {
  const HandTrialScene& scene = *this;
  io::GripperRecord record;
  record.name = setting_name(scene.name(), scene.hand_count());
  record.kind = "hand";
  record.hands = static_cast<std::uint32_t>(scene.hand_count());
  // Names and sizes are per hand: every hand must have the first one's joints and fingers.
  const auto joint_names = [&](int h) {
    std::vector<std::string> names;
    const grippers::KinematicTree& tree = scene.kinematics(h);
    for (int dof = 0; dof < tree.dof_count(); ++dof) names.push_back(tree.dof_joint(dof).name);
    return names;
  };
  record.joint_names = joint_names(0);
  std::vector<std::size_t> fingers(record.hands, 0);
  for (const HandFinger& finger : scene.fingers()) {
    if (finger.hand == 0) record.finger_names.push_back(finger.name);
    ++fingers[static_cast<std::size_t>(finger.hand)];
  }
  for (int h = 1; h < scene.hand_count(); ++h) {
    if (joint_names(h) != record.joint_names || fingers[h] != fingers[0] ||
        scene.hand_rest_surface(h).vertices.rows() != scene.hand_rest_surface(0).vertices.rows()) {
      throw std::invalid_argument("gripper record of '" + scene.name() + "': hand " +
                                  std::to_string(h) +
                                  " differs from the first in its joints, fingers or surface size");
    }
  }
  for (int h = 0; h < scene.hand_count(); ++h) add_surface(record, scene.hand_rest_surface(h));
  return record;
}

}  // namespace grip::trial
