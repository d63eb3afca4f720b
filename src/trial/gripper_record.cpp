#include "src/trial/gripper_record.hpp"

namespace grip::trial {

namespace {

void set_surface(io::GripperRecord& record, const geometry::SurfaceMesh& surface) {
  record.vertices.assign(surface.vertices.data(),
                         surface.vertices.data() + surface.vertices.size());
  record.triangles.assign(surface.triangles.data(),
                          surface.triangles.data() + surface.triangles.size());
}

}  // namespace

io::GripperRecord gripper_record(const TrialScene& scene) {
  const grippers::ParallelGripper& gripper = scene.gripper();
  io::GripperRecord record;
  record.name = gripper.name;
  record.kind = "parallel";
  record.soft = gripper.soft_finger.has_value();
  record.joint_names = {"opening"};
  record.finger_names = {"positive", "negative"};
  set_surface(record, gripper.surface(gripper.max_opening));
  return record;
}

io::GripperRecord gripper_record(const HandTrialScene& scene) {
  const grippers::KinematicTree& tree = scene.kinematics();
  io::GripperRecord record;
  record.name = scene.name();
  record.kind = "hand";
  for (int dof = 0; dof < tree.dof_count(); ++dof) {
    record.joint_names.push_back(tree.dof_joint(dof).name);
  }
  for (const HandFinger& finger : scene.fingers()) record.finger_names.push_back(finger.name);
  set_surface(record, scene.rest_surface());
  return record;
}

}  // namespace grip::trial
