#include "io/dataset_layout.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

#include "io/checksum.hpp"
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

std::string finger_stress_dataset(std::uint32_t gripper) {
  return gripper_group(gripper) + "/finger_stress";
}

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
    if (gripper.vertices.size() % 3 != 0 || gripper.triangles.size() % 3 != 0 ||
        gripper.tet_vertices.size() % 3 != 0 || gripper.tets.size() % 4 != 0) {
      plan_error("gripper " + std::to_string(g) + " ('" + gripper.name +
                 "') has vertices, triangles or tets that are not whole (3, 3, 4 values)");
    }
    const auto tet_vertices = static_cast<std::int64_t>(gripper.tet_vertices.size() / 3);
    if (std::any_of(gripper.tets.begin(), gripper.tets.end(),
                    [&](std::int32_t i) { return i < 0 || i >= tet_vertices; })) {
      plan_error("gripper " + std::to_string(g) + " ('" + gripper.name +
                 "') has a tet index outside its " + std::to_string(tet_vertices) +
                 " tet vertices");
    }
    if (gripper.vertex_count() % gripper.hands != 0) {
      plan_error("gripper " + std::to_string(g) + " ('" + gripper.name + "') has " +
                 std::to_string(gripper.vertex_count()) +
                 " vertices, not as many for each of its " + std::to_string(gripper.hands) +
                 " hands");
    }
    const Gripper sizes{gripper.hands,
                        static_cast<std::uint32_t>(gripper.joint_names.size()),
                        static_cast<std::uint32_t>(gripper.finger_names.size()),
                        gripper.vertex_count() / gripper.hands,
                        gripper.tets.size() / 4,
                        0};
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
    const GripperRecord& gripper = plan.grippers[slot.gripper];
    if (slot.finger_stress && (!gripper.soft || gripper.tets.empty())) {
      plan_error("candidate " + std::to_string(id) + " asks for finger stress, but gripper '" +
                 gripper.name + "' has no soft fingers with tets");
    }
    layout.object.push_back(slot.object);
    layout.gripper.push_back(slot.gripper);
    auto& frame_slots = layout.trajectory_slots[layout.pair(slot.object, slot.gripper)];
    layout.frame_slot.push_back(slot.frames ? static_cast<std::int64_t>(frame_slots++) : -1);
    auto& stress_slots = layout.objects[slot.object].stress_slots;
    layout.stress_slot.push_back(slot.stress ? static_cast<std::int64_t>(stress_slots++) : -1);
    auto& finger_slots = layout.grippers[slot.gripper].stress_slots;
    layout.finger_stress_slot.push_back(
        slot.finger_stress ? static_cast<std::int64_t>(finger_slots++) : -1);
  }
  return layout;
}

namespace {

std::string shape_text(const Dims& dims) {
  std::string text = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) {
    text += (i > 0 ? ", " : "") + std::to_string(dims[i]);
  }
  return text + ")";
}

// The dataset at `path`, which must have the shape `expected`.
h5::Handle open_shaped(hid_t file, const std::string& path, const Dims& expected) {
  h5::Handle dataset = h5::open_dataset(file, path);
  const Dims found = h5::dims(dataset);
  if (found != expected) {
    throw DatasetError(path + " has shape " + shape_text(found) + ", expected " +
                       shape_text(expected));
  }
  return dataset;
}

// The rows of the dataset at `path`, whose other extents must be `row`.
std::uint64_t rows_of(hid_t file, const std::string& path, const Dims& row) {
  const Dims found = h5::dims(h5::open_dataset(file, path));
  if (found.size() != row.size() + 1 || !std::equal(row.begin(), row.end(), found.begin() + 1)) {
    std::string expected = "(rows";
    for (const hsize_t extent : row) expected += ", " + std::to_string(extent);
    throw DatasetError(path + " has shape " + shape_text(found) + ", expected " + expected + ")");
  }
  return found[0];
}

// An attribute holding a count from `low` to `high`.
std::uint32_t count_attribute(hid_t object, const std::string& where, const std::string& name,
                              std::uint64_t low, std::uint64_t high) {
  const std::uint64_t value = h5::read_uint_attribute(object, name);
  if (value < low || value > high) {
    throw DatasetError("attribute '" + name + "' of " + where + " is " + std::to_string(value) +
                       " (valid: " + std::to_string(low) + " to " + std::to_string(high) + ")");
  }
  return static_cast<std::uint32_t>(value);
}

// "1 object", "3 objects".
std::string counted(std::uint64_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// "valid: 0 to 2", "valid: -1, or 0 to 2" where -1 (none) is allowed, "valid: -1" or "valid:
// none" for an empty range.
std::string valid_range(std::uint64_t count, bool none_allowed) {
  std::string text = none_allowed ? "-1" : "";
  if (count > 0) text += (none_allowed ? ", or 0 to " : "0 to ") + std::to_string(count - 1);
  return "valid: " + (text.empty() ? std::string("none") : text);
}

// Every stored index is checked against the sizes it indexes before anything uses it.
void check_plan_indices(const DatasetLayout& layout) {
  const std::size_t objects = layout.objects.size();
  const std::size_t grippers = layout.grippers.size();
  for (std::uint64_t id = 0; id < layout.candidate_count; ++id) {
    const auto bad = [id](const char* column, std::int64_t value, const std::string& why) {
      throw DatasetError(std::string("/candidates/") + column + " row " + std::to_string(id) +
                         " is " + std::to_string(value) + ", " + why);
    };
    const std::uint32_t o = layout.object[id];
    const std::uint32_t g = layout.gripper[id];
    if (o >= objects) {
      bad("object", o,
          "outside the " + counted(objects, "object") + " (" + valid_range(objects, false) + ")");
    }
    if (g >= grippers) {
      bad("gripper", g,
          "outside the " + counted(grippers, "gripper") + " (" + valid_range(grippers, false) +
              ")");
    }
    const std::uint64_t frame_slots = layout.trajectory_slots[layout.pair(o, g)];
    const std::int64_t frame = layout.frame_slot[id];
    if (frame < -1 || (frame >= 0 && static_cast<std::uint64_t>(frame) >= frame_slots)) {
      bad("frame_slot", frame,
          "outside the " + counted(frame_slots, "row") + " of " + trajectory_group(o, g) + " (" +
              valid_range(frame_slots, true) + ")");
    }
    const std::uint64_t stress_slots = layout.objects[o].stress_slots;
    const std::int64_t stress = layout.stress_slot[id];
    if (stress < -1 || (stress >= 0 && static_cast<std::uint64_t>(stress) >= stress_slots)) {
      bad("stress_slot", stress,
          "outside the " + counted(stress_slots, "row") + " of " + stress_dataset(o) + " (" +
              valid_range(stress_slots, true) + ")");
    }
    const std::uint64_t finger_slots = layout.grippers[g].stress_slots;
    const std::int64_t finger = layout.finger_stress_slot[id];
    if (finger < -1 || (finger >= 0 && static_cast<std::uint64_t>(finger) >= finger_slots)) {
      bad("finger_stress_slot", finger,
          "outside the " + counted(finger_slots, "row") + " of " + finger_stress_dataset(g) + " (" +
              valid_range(finger_slots, true) + ")");
    }
  }
}

// Each object's sizes, from its meshes' and stress dataset's shapes.
void read_objects(hid_t file, std::uint32_t count, DatasetLayout& layout) {
  for (std::uint32_t o = 0; o < count; ++o) {
    const std::string group = object_group(o);
    DatasetLayout::Object object;
    object.vertices = rows_of(file, group + "/vertices", {3});
    rows_of(file, group + "/triangles", {3});
    object.tets = rows_of(file, group + "/tets", {4});
    if (h5::exists(file, stress_dataset(o))) {
      object.stress_slots = rows_of(file, stress_dataset(o), {object.tets});
    }
    layout.objects.push_back(object);
  }
}

// Each gripper's sizes, within the table's widths.
void read_grippers(hid_t file, std::uint32_t count, DatasetLayout& layout) {
  for (std::uint32_t g = 0; g < count; ++g) {
    const std::string path = gripper_group(g);
    const h5::Handle group =
        h5::group_handle(H5Gopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
    DatasetLayout::Gripper gripper;
    gripper.hands = count_attribute(group, path, "hands", 1, layout.max_hands);
    gripper.joints = static_cast<std::uint32_t>(rows_of(file, path + "/joint_names", {}));
    gripper.fingers = static_cast<std::uint32_t>(rows_of(file, path + "/finger_names", {}));
    const std::uint64_t vertices = rows_of(file, path + "/vertices", {3});
    if (vertices % gripper.hands != 0) {
      throw DatasetError(path + "/vertices has " + std::to_string(vertices) +
                         " rows, not as many for each of its " + std::to_string(gripper.hands) +
                         " hands");
    }
    gripper.vertices = vertices / gripper.hands;
    rows_of(file, path + "/triangles", {3});
    rows_of(file, path + "/tet_vertices", {3});
    gripper.tets = rows_of(file, path + "/tets", {4});
    if (h5::exists(file, finger_stress_dataset(g))) {
      gripper.stress_slots = rows_of(file, finger_stress_dataset(g), {gripper.tets});
    }
    if (gripper.joints > layout.max_joints || gripper.fingers > layout.max_fingers) {
      throw DatasetError(path + " has " + std::to_string(gripper.joints) + " joints and " +
                         std::to_string(gripper.fingers) + " fingers, more than the table's " +
                         std::to_string(layout.max_joints) + " and " +
                         std::to_string(layout.max_fingers));
    }
    layout.grippers.push_back(gripper);
  }
}

// The trajectory slots of each (object, gripper) pair: the rows of its trajectory datasets,
// each shaped for the pair.
void read_trajectory_slots(hid_t file, DatasetLayout& layout) {
  const auto objects = static_cast<std::uint32_t>(layout.objects.size());
  const auto grippers = static_cast<std::uint32_t>(layout.grippers.size());
  layout.trajectory_slots.assign(std::size_t{objects} * grippers, 0);
  for (std::uint32_t o = 0; o < objects; ++o) {
    if (!h5::exists(file, object_group(o) + "/trajectories")) continue;
    for (std::uint32_t g = 0; g < grippers; ++g) {
      const std::string group = trajectory_group(o, g);
      if (!h5::exists(file, group)) continue;
      const Sizes sizes = Sizes::of(layout, o, g);
      // The first column's rows are the slots; the others must have as many.
      std::optional<std::uint64_t> slots;
      std::string first;
      for (const Column& column : dataset_columns()) {
        if (column.place != Place::kTrajectory) continue;
        const std::string path = group + "/" + column.name;
        const std::uint64_t rows = rows_of(file, path, column.extents(sizes));
        if (slots && rows != *slots) {
          throw DatasetError(path + " has " + std::to_string(rows) + " rows, but " + first +
                             " has " + std::to_string(*slots));
        }
        if (!slots) first = path;
        slots = rows;
      }
      layout.trajectory_slots[layout.pair(o, g)] = slots.value_or(0);
    }
  }
}

// The candidate table: every column's shape, then the plan's values, their ranges and the
// checksums written with them.
void read_candidate_table(hid_t file, DatasetLayout& layout) {
  const Sizes table = Sizes::of(layout);
  std::vector<std::pair<h5::Handle, Values>> plan;
  for (const Column& column : dataset_columns()) {
    if (column.place != Place::kPlan && column.place != Place::kDone &&
        column.place != Place::kChecksum && column.place != Place::kResult) {
      continue;
    }
    Dims dims{layout.candidate_count};
    const Dims row = column.extents(table);
    dims.insert(dims.end(), row.begin(), row.end());
    h5::Handle dataset = open_shaped(file, std::string("/candidates/") + column.name, dims);
    if (column.place != Place::kPlan) continue;
    Values values = read_values(dataset, column.element);
    column.access_to<DatasetLayout>().put(values, layout);
    plan.emplace_back(std::move(dataset), std::move(values));
  }
  check_plan_indices(layout);
  auto next = plan.begin();
  for (const Column& column : dataset_columns()) {
    if (column.place != Place::kPlan) continue;
    verify_whole_checksum(next->first, std::string("/candidates/") + column.name, next->second);
    ++next;
  }
}

}  // namespace

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
                       ", this grip reads version " + std::to_string(kFormatVersion) +
                       " (read it with the grip that made it, or run its job again into a new "
                       "file)");
  }
  constexpr std::uint64_t kMaxCount = std::numeric_limits<std::uint32_t>::max();
  layout.candidate_count = h5::read_uint_attribute(file, "candidate_count");
  layout.closing_frames = count_attribute(file, "/", "closing_frames", 0, kMaxCount);
  layout.validation_frames =
      count_attribute(file, "/", "validation_frames", 0, kMaxCount - layout.closing_frames);
  layout.max_hands = count_attribute(file, "/", "max_hands", 1, 2);
  layout.max_joints = count_attribute(file, "/", "max_joints", 1, kMaxCount);
  layout.max_fingers = count_attribute(file, "/", "max_fingers", 1, kMaxCount);
  const std::uint32_t object_count = count_attribute(file, "/", "object_count", 0, kMaxCount);
  const std::uint32_t gripper_count = count_attribute(file, "/", "gripper_count", 0, kMaxCount);

  read_objects(file, object_count, layout);
  read_grippers(file, gripper_count, layout);
  read_trajectory_slots(file, layout);
  read_candidate_table(file, layout);
  return layout;
}

}  // namespace grip::io
