#include "src/trial/gripper_record.hpp"

#include <stdexcept>

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

// A bimanual setting is its own gripper record, named apart from the one-gripper setting.
std::string setting_name(const std::string& name, int hands) {
  return hands == 2 ? name + "-bimanual" : name;
}

}  // namespace

io::GripperRecord gripper_record(const TrialScene& scene) {
  const grippers::ParallelGripper& gripper = scene.gripper();
  io::GripperRecord record;
  record.name = setting_name(gripper.name, scene.gripper_count());
  record.kind = "parallel";
  record.hands = static_cast<std::uint32_t>(scene.gripper_count());
  record.soft = gripper.soft_finger.has_value();
  record.joint_names = {"opening"};
  record.finger_names = {"positive", "negative"};
  const geometry::SurfaceMesh surface = gripper.surface(gripper.max_opening);
  for (int g = 0; g < scene.gripper_count(); ++g) add_surface(record, surface);
  return record;
}

io::GripperRecord gripper_record(const HandTrialScene& scene) {
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
