#include "io/dataset_layout.hpp"

#include <algorithm>
#include <cstdio>

#include "io/dataset_columns.hpp"
#include "io/dataset_error.hpp"
#include "io/hdf5.hpp"

namespace grip::io {

std::string object_group(std::uint32_t object) {
  char name[32];
  std::snprintf(name, sizeof name, "/objects/%06u", object);
  return name;
}

std::string gripper_group(std::uint32_t gripper) {
  char name[32];
  std::snprintf(name, sizeof name, "/grippers/%03u", gripper);
  return name;
}

std::string trajectory_group(std::uint32_t object, std::uint32_t gripper) {
  char name[24];
  std::snprintf(name, sizeof name, "/trajectories/%03u", gripper);
  return object_group(object) + name;
}

std::string stress_dataset(std::uint32_t object) { return object_group(object) + "/stress"; }

namespace {

[[noreturn]] void plan_error(const std::string& message) {
  throw DatasetError("dataset plan: " + message);
}

}  // namespace

DatasetLayout DatasetLayout::from_plan(const DatasetPlan& plan) {
  DatasetLayout layout;
  layout.candidate_count = plan.candidates.size();
  layout.closing_frames = plan.closing_frames;
  layout.validation_frames = plan.validation_frames;
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    const ObjectRecord& object = plan.objects[o];
    const std::string which = "object " + std::to_string(o) + " ('" + object.name + "')";
    if (object.vertices.size() % 3 != 0 || object.triangles.size() % 3 != 0 ||
        object.tets.size() % 4 != 0) {
      plan_error(which + " has vertices, triangles or tets that are not whole (3, 3, 4 values)");
    }
    const auto n = static_cast<std::int64_t>(object.vertex_count());
    const auto out_of_range = [n](std::int32_t i) { return i < 0 || i >= n; };
    if (std::any_of(object.triangles.begin(), object.triangles.end(), out_of_range) ||
        std::any_of(object.tets.begin(), object.tets.end(), out_of_range)) {
      plan_error(which + " has a triangle or tet index outside its " + std::to_string(n) +
                 " vertices");
    }
    layout.objects.push_back({object.vertex_count(), object.tet_count(), 0});
  }
  for (std::size_t g = 0; g < plan.grippers.size(); ++g) {
    const GripperRecord& gripper = plan.grippers[g];
    if (gripper.hands < 1 || gripper.hands > 2) {
      plan_error("gripper " + std::to_string(g) + " ('" + gripper.name + "') has " +
                 std::to_string(gripper.hands) + " hands; use 1, or 2 for bimanual");
    }
    if (gripper.vertices.size() % 3 != 0 || gripper.triangles.size() % 3 != 0) {
      plan_error("gripper " + std::to_string(g) + " ('" + gripper.name +
                 "') has vertices or triangles that are not whole (3 values each)");
    }
    const Gripper sizes{gripper.hands, static_cast<std::uint32_t>(gripper.joint_names.size()),
                        static_cast<std::uint32_t>(gripper.finger_names.size()),
                        gripper.vertex_count()};
    layout.grippers.push_back(sizes);
    layout.max_hands = std::max(layout.max_hands, sizes.hands);
    layout.max_joints = std::max(layout.max_joints, sizes.joints);
    layout.max_fingers = std::max(layout.max_fingers, sizes.fingers);
  }
  layout.trajectory_slots.assign(plan.objects.size() * plan.grippers.size(), 0);
  for (std::size_t id = 0; id < plan.candidates.size(); ++id) {
    const CandidateSlot& slot = plan.candidates[id];
    if (slot.object >= plan.objects.size() || slot.gripper >= plan.grippers.size()) {
      plan_error("candidate " + std::to_string(id) + " names object " +
                 std::to_string(slot.object) + " and gripper " + std::to_string(slot.gripper) +
                 ", but the plan has " + std::to_string(plan.objects.size()) + " objects and " +
                 std::to_string(plan.grippers.size()) + " grippers");
    }
    const ObjectRecord& object = plan.objects[slot.object];
    if (slot.stress && (!object.soft || object.tets.empty())) {
      plan_error("candidate " + std::to_string(id) + " asks for stress, but object '" +
                 object.name + "' is not a soft object with tets");
    }
    layout.object.push_back(slot.object);
    layout.gripper.push_back(slot.gripper);
    auto& frame_slots = layout.trajectory_slots[layout.pair(slot.object, slot.gripper)];
    layout.frame_slot.push_back(slot.frames ? static_cast<std::int64_t>(frame_slots++) : -1);
    auto& stress_slots = layout.objects[slot.object].stress_slots;
    layout.stress_slot.push_back(slot.stress ? static_cast<std::int64_t>(stress_slots++) : -1);
  }
  return layout;
}

DatasetLayout DatasetLayout::read(hid_t file) {
  DatasetLayout layout;
  if (H5Aexists(file, "format") <= 0) {
    throw DatasetError("it is an HDF5 file but not a grip dataset (it has no 'format' attribute)");
  }
  const std::string format = h5::read_string_attribute(file, "format");
  if (format != kFormatName) {
    throw DatasetError("it is an HDF5 file but not a grip dataset (format '" + format + "')");
  }
  const std::uint64_t version = h5::read_uint_attribute(file, "format_version");
  if (version != kFormatVersion) {
    throw DatasetError("it is grip dataset format version " + std::to_string(version) +
                       ", this grip reads version " + std::to_string(kFormatVersion));
  }
  layout.candidate_count = h5::read_uint_attribute(file, "candidate_count");
  layout.closing_frames =
      static_cast<std::uint32_t>(h5::read_uint_attribute(file, "closing_frames"));
  layout.validation_frames =
      static_cast<std::uint32_t>(h5::read_uint_attribute(file, "validation_frames"));
  layout.max_hands = static_cast<std::uint32_t>(h5::read_uint_attribute(file, "max_hands"));
  layout.max_joints = static_cast<std::uint32_t>(h5::read_uint_attribute(file, "max_joints"));
  layout.max_fingers = static_cast<std::uint32_t>(h5::read_uint_attribute(file, "max_fingers"));
  const auto object_count =
      static_cast<std::uint32_t>(h5::read_uint_attribute(file, "object_count"));
  const auto gripper_count =
      static_cast<std::uint32_t>(h5::read_uint_attribute(file, "gripper_count"));

  const auto open = [file](const std::string& path) {
    return h5::dataset_handle(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
  };
  for (std::uint32_t o = 0; o < object_count; ++o) {
    Object object;
    object.vertices = h5::dims(open(object_group(o) + "/vertices"))[0];
    object.tets = h5::dims(open(object_group(o) + "/tets"))[0];
    if (h5::exists(file, stress_dataset(o))) {
      object.stress_slots = h5::dims(open(stress_dataset(o)))[0];
    }
    layout.objects.push_back(object);
  }
  for (std::uint32_t g = 0; g < gripper_count; ++g) {
    const h5::Handle group = h5::group_handle(H5Gopen2(file, gripper_group(g).c_str(), H5P_DEFAULT),
                                              "opening " + gripper_group(g));
    Gripper gripper;
    gripper.hands = static_cast<std::uint32_t>(h5::read_uint_attribute(group, "hands"));
    gripper.joints =
        static_cast<std::uint32_t>(h5::dims(open(gripper_group(g) + "/joint_names"))[0]);
    gripper.fingers =
        static_cast<std::uint32_t>(h5::dims(open(gripper_group(g) + "/finger_names"))[0]);
    gripper.vertices = h5::dims(open(gripper_group(g) + "/vertices"))[0];
    layout.grippers.push_back(gripper);
  }
  for (const Column& column : dataset_columns()) {
    if (column.place != Place::kPlan) continue;
    const h5::Handle dataset = open(std::string("/candidates/") + column.name);
    column.access_to<DatasetLayout>().put(read_values(dataset, column.element), layout);
  }
  if (layout.object.size() != layout.candidate_count) {
    throw DatasetError("its candidate table has " + std::to_string(layout.object.size()) +
                       " rows, but its header says " + std::to_string(layout.candidate_count));
  }
  layout.trajectory_slots.assign(std::size_t{object_count} * gripper_count, 0);
  for (std::uint32_t o = 0; o < object_count; ++o) {
    for (std::uint32_t g = 0; g < gripper_count; ++g) {
      const std::string path = trajectory_group(o, g) + "/object_vertices";
      if (h5::exists(file, object_group(o) + "/trajectories") &&
          h5::exists(file, trajectory_group(o, g))) {
        layout.trajectory_slots[layout.pair(o, g)] = h5::dims(open(path))[0];
      }
    }
  }
  return layout;
}

}  // namespace grip::io
