#include "io/grip_layout.hpp"

#include <hdf5.h>

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <system_error>
#include <type_traits>
#include <utility>
#include <variant>

#include "io/dataset_error.hpp"
#include "io/hdf5.hpp"

namespace grip::io {
namespace {

using Dims = std::vector<hsize_t>;

// One exported file while it is written: its datasets are created whole, then filled pose by
// pose along the leading axis.
class LayoutFile {
 public:
  explicit LayoutFile(const std::filesystem::path& path)
      : name_(path.string()),
        file_(h5::file_handle(H5Fcreate(name_.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT),
                              "creating " + name_)) {
    for (const char* group : {"object_config", "trajectories"}) {
      h5::group_handle(H5Gcreate2(file_, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       name_ + ": creating " + group);
    }
  }

  hid_t file() const { return file_; }

  void scalar(const std::string& name, double value) {
    const h5::Handle space = h5::space_handle(H5Screate(H5S_SCALAR), name);
    const h5::Handle set = create(name, H5T_IEEE_F64LE, space);
    h5::check(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value),
              name_ + ": writing " + name);
  }

  void scalar(const std::string& name, const std::string& value) {
    const h5::Handle space = h5::space_handle(H5Screate(H5S_SCALAR), name);
    const h5::Handle type = h5::string_type(std::max<std::size_t>(value.size(), 1));
    const h5::Handle set = create(name, type, space);
    std::string padded = value;
    padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
    h5::check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, padded.data()),
              name_ + ": writing " + name);
  }

  // A dataset of `dims`, created now and filled row by row (row()).
  h5::Handle dataset(const std::string& name, hid_t type, const Dims& dims) {
    const h5::Handle space = h5::space_handle(
        H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), name);
    return create(name, type, space);
  }

  // Writes row `row` of the leading axis of `set` from `data` (the row's elements in order).
  void row(hid_t set, const std::string& name, hid_t memory_type, hsize_t row, const void* data) {
    Dims dims = h5::dims(set);
    const h5::Handle file_space = h5::space_handle(H5Dget_space(set), name);
    Dims start(dims.size(), 0);
    start[0] = row;
    dims[0] = 1;
    h5::check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, dims.data(),
                                  nullptr),
              name_ + ": selecting a row of " + name);
    const h5::Handle memory = h5::space_handle(
        H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), name);
    h5::check(H5Dwrite(set, memory_type, memory, file_space, H5P_DEFAULT, data),
              name_ + ": writing " + name);
  }

  // A dataset written whole.
  void whole(const std::string& name, hid_t type, hid_t memory_type, const Dims& dims,
             const void* data) {
    const h5::Handle set = dataset(name, type, dims);
    h5::check(H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
              name_ + ": writing " + name);
  }

 private:
  h5::Handle create(const std::string& name, hid_t type, hid_t space) {
    return h5::dataset_handle(
        H5Dcreate2(file_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        name_ + ": creating " + name);
  }

  std::string name_;
  h5::Handle file_;
};

// One grasp's row of a per-pose dataset: float32 frames or float64 states.
using Row = std::variant<std::vector<float>, std::vector<double>>;

// A dataset with a leading pose axis, and how one grasp's row is made from its trajectory.
struct PoseSeries {
  std::string name;
  h5::Handle set;
  std::function<Row(std::uint64_t id, const TrajectoryRecord&)> row;
};

// Shapes of the per-hand arrays: GRIP's single-hand shape, with a hands axis after the frames
// (or after the pose, for per-pose meshes) only for a bimanual setting.
Dims with_hands(std::uint32_t hands, Dims shape, std::size_t hands_at) {
  if (hands > 1) shape.insert(shape.begin() + static_cast<std::ptrdiff_t>(hands_at), hands);
  return shape;
}

// Rows [first, first + count) of each hand's block of `per_hand` rows (3 floats each), frame
// after frame: one finger's vertices or forces out of the gripper's.
std::vector<float> hand_rows(const std::vector<float>& values, std::size_t frames,
                             std::uint32_t hands, std::size_t per_hand, std::size_t first,
                             std::size_t count) {
  std::vector<float> out;
  out.reserve(frames * hands * count * 3);
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::uint32_t h = 0; h < hands; ++h) {
      const std::size_t begin = ((f * hands + h) * per_hand + first) * 3;
      out.insert(out.end(), values.begin() + static_cast<std::ptrdiff_t>(begin),
                 values.begin() + static_cast<std::ptrdiff_t>(begin + count * 3));
    }
  }
  return out;
}

// The triangles of each hand whose corners all lie in [first, first + count) of the hand's
// vertices, renumbered from 0: one finger's surface (or the whole hand's), hand after hand.
// Throws DatasetError when the hands' parts differ in triangle count: GRIP's layout holds them
// in one array.
std::vector<std::int32_t> hand_triangles(const GripperRecord& gripper, std::size_t per_hand,
                                         std::size_t first, std::size_t count) {
  std::vector<std::int32_t> out;
  std::size_t first_hand = 0;
  for (std::uint32_t h = 0; h < gripper.hands; ++h) {
    const std::size_t before = out.size();
    const auto lo = static_cast<std::int32_t>(h * per_hand + first);
    const auto hi = lo + static_cast<std::int32_t>(count);
    for (std::size_t t = 0; t + 2 < gripper.triangles.size(); t += 3) {
      const std::int32_t* c = &gripper.triangles[t];
      if (std::all_of(c, c + 3, [&](std::int32_t v) { return v >= lo && v < hi; })) {
        for (int k = 0; k < 3; ++k) out.push_back(c[k] - lo);
      }
    }
    if (h == 0) first_hand = out.size();
    if (out.size() - before != first_hand) {
      throw DatasetError("gripper '" + gripper.name +
                         "': its hands' surfaces differ in triangles, which GRIP's layout "
                         "cannot hold in one array");
    }
  }
  return out;
}

std::string file_name_part(std::string text) {
  for (char& c : text) {
    if (c == '/' || c == '\\' || c == ' ' || c == '_') c = '-';
  }
  return text;
}

// What one file holds: its gripper, object and the candidates kept, in id order.
struct PairExport {
  std::uint32_t object = 0;
  std::uint32_t gripper = 0;
  std::vector<std::uint64_t> ids;
  std::filesystem::path path;
};

class PairWriter {
 public:
  PairWriter(const DatasetReader& dataset, const std::vector<CandidateRecord>& records,
             const PairExport& pair)
      : dataset_(dataset),
        records_(records),
        pair_(pair),
        object_(dataset.object(pair.object)),
        gripper_(dataset.gripper(pair.gripper)),
        frames_(dataset.layout().frames()),
        per_hand_(dataset.layout().grippers[pair.gripper].vertices),
        parallel_(gripper_.kind == "parallel") {}

  void write(const std::filesystem::path& path) {
    if (parallel_ && per_hand_ % 2 != 0) {
      throw DatasetError(dataset_.path().string() + ": gripper '" + gripper_.name + "' has " +
                         std::to_string(per_hand_) +
                         " surface vertices per hand, not two fingers' alike: GRIP's layout "
                         "needs a left and a right finger");
    }
    LayoutFile file(path);
    write_object_config(file);
    write_meshes(file);
    write_verdicts(file);
    write_frames(file);
  }

 private:
  hsize_t poses() const { return pair_.ids.size(); }

  void write_object_config(LayoutFile& file) {
    // GRIP's own reader takes object_type for the material ("rigid" or "soft"); the category
    // goes to object_category.
    file.scalar("object_config/object_type", std::string(object_.soft ? "soft" : "rigid"));
    file.scalar("object_config/object_category", object_.category);
    file.scalar("object_config/object_name", object_.name);
    file.scalar("object_config/object_density", object_.material.density);
    file.scalar("object_config/object_youngs", object_.material.young_modulus);
    file.scalar("object_config/object_poisson", object_.material.poisson_ratio);
    file.scalar("object_config/object_fric", object_.material.friction);
    // grip's trials hold the object in the air: there is no ground.
    file.scalar("object_config/ground_fric", std::numeric_limits<double>::quiet_NaN());
    file.scalar("object_config/object_scale", object_.scale);
  }

  // Meshes repeated per pose, as GRIP stores them; a soft object's tets once.
  void write_meshes(LayoutFile& file) {
    const auto each_pose = [&](const std::string& name, const std::vector<std::int32_t>& values,
                               Dims shape) {
      std::vector<std::int32_t> all;
      for (hsize_t p = 0; p < poses(); ++p) all.insert(all.end(), values.begin(), values.end());
      shape.insert(shape.begin(), poses());
      file.whole(name, H5T_STD_I32LE, H5T_NATIVE_INT32, shape, all.data());
    };
    const std::uint32_t hands = gripper_.hands;
    for (const Part& part : parts()) {
      const std::vector<std::int32_t> triangles =
          hand_triangles(gripper_, per_hand_, part.first, part.count);
      each_pose("trajectories/" + part.name + "_faces", triangles,
                with_hands(hands, {triangles.size() / 3 / hands, 3}, 0));
    }
    if (object_.soft) {
      file.whole("trajectories/object_cells", H5T_STD_I32LE, H5T_NATIVE_INT32,
                 {object_.tet_count(), 4}, object_.tets.data());
    } else {
      each_pose("trajectories/object_faces", object_.triangles, {object_.triangles.size() / 3, 3});
    }
  }

  void write_verdicts(LayoutFile& file) {
    std::vector<std::uint64_t> ids = pair_.ids;
    std::vector<std::uint8_t> success;
    std::vector<std::uint32_t> simulated;
    std::string failures;
    std::size_t width = 1;
    for (const std::uint64_t id : ids) {
      width = std::max(width, to_string(records_[id].failure).size());
    }
    for (const std::uint64_t id : ids) {
      const CandidateRecord& r = records_[id];
      success.push_back(r.status == Status::kSuccess ? 1 : 0);
      simulated.push_back(r.simulated_frames);
      std::string failure(to_string(r.failure));
      failure.resize(width, '\0');
      failures += failure;
    }
    file.whole("trajectories/candidate_id", H5T_STD_U64LE, H5T_NATIVE_UINT64, {poses()},
               ids.data());
    file.whole("trajectories/success", H5T_STD_U8LE, H5T_NATIVE_UINT8, {poses()}, success.data());
    file.whole("trajectories/simulated_frames", H5T_STD_U32LE, H5T_NATIVE_UINT32, {poses()},
               simulated.data());
    const h5::Handle type = h5::string_type(width);
    file.whole("trajectories/failure", type, type, {poses()}, failures.data());
  }

  // A gripper's surface part: a parallel gripper's left (+y jaw) and right finger, or a hand.
  struct Part {
    std::string name;
    std::size_t first = 0;
    std::size_t count = 0;
  };
  std::vector<Part> parts() const {
    if (!parallel_) return {{"hand", 0, per_hand_}};
    return {{"leftfinger", 0, per_hand_ / 2}, {"rightfinger", per_hand_ / 2, per_hand_ / 2}};
  }
  // The key prefix of joint and pose states: GRIP's for a two-finger gripper, the name else.
  std::string prefix() const { return parallel_ ? "finray" : file_name_part(gripper_.name); }

  void write_frames(LayoutFile& file) {
    const std::uint32_t hands = gripper_.hands;
    const hsize_t F = frames_;
    const hsize_t joints = parallel_ ? 3 : gripper_.joint_names.size();
    std::vector<PoseSeries> series;
    const auto add = [&](const std::string& name, hid_t type, Dims shape, auto row) {
      shape.insert(shape.begin(), poses());
      series.push_back({name, file.dataset("trajectories/" + name, type, shape), row});
    };
    const auto state = [&](const std::string& name, Dims shape, auto values) {
      add(name, H5T_IEEE_F64LE, with_hands(hands, std::move(shape), 1),
          [values](std::uint64_t, const TrajectoryRecord& t) { return Row(values(t)); });
    };
    state(prefix() + "_joint_states", {F, joints},
          [this](const TrajectoryRecord& t) { return joint_states(t); });
    state(prefix() + "_tf_states", {F, 4, 4}, [](const TrajectoryRecord& t) {
      return pose_columns(t, 0, 4, {0.0, 0.0, 0.0, 1.0});
    });
    state("hand_translation", {F, 3},
          [](const TrajectoryRecord& t) { return pose_columns(t, 3, 1, {}); });
    state("hand_rotation", {F, 3, 3},
          [](const TrajectoryRecord& t) { return pose_columns(t, 0, 3, {}); });
    for (const Part& part : parts()) {
      const std::string side = parallel_ ? part.name.substr(0, part.name.size() - 6) : part.name;
      for (const auto& [name, values] :
           {std::pair{part.name + "_points", &TrajectoryRecord::gripper_vertices},
            std::pair{side + "_f_collisions", &TrajectoryRecord::gripper_contact_forces},
            std::pair{side + "_f_frictions", &TrajectoryRecord::gripper_friction_forces}}) {
        add(name, H5T_IEEE_F32LE, with_hands(hands, {F, part.count, 3}, 1),
            [this, part, values = values](std::uint64_t, const TrajectoryRecord& t) {
              return Row(
                  hand_rows(t.*values, frames_, gripper_.hands, per_hand_, part.first, part.count));
            });
      }
    }
    const hsize_t n = object_.vertex_count();
    for (const auto& [name, values] :
         {std::pair{std::string(object_.soft ? "object_points" : "object_vertices"),
                    &TrajectoryRecord::object_vertices},
          std::pair{std::string("object_f_collisions"), &TrajectoryRecord::contact_forces},
          std::pair{std::string("object_f_frictions"), &TrajectoryRecord::friction_forces}}) {
      add(name, H5T_IEEE_F32LE, {F, n, 3},
          [values = values](std::uint64_t, const TrajectoryRecord& t) { return Row(t.*values); });
    }
    if (object_.soft && object_.tet_count() > 0) {
      add("object_stress", H5T_IEEE_F32LE, {object_.tet_count()},
          [this](std::uint64_t id, const TrajectoryRecord&) {
            return Row(dataset_.stress(id).value_or(
                std::vector<float>(object_.tet_count(), std::numeric_limits<float>::quiet_NaN())));
          });
    }

    for (hsize_t p = 0; p < poses(); ++p) {
      const std::uint64_t id = pair_.ids[p];
      const std::optional<TrajectoryRecord> t = dataset_.trajectory(id);
      if (!t)
        throw DatasetError(dataset_.path().string() + ": candidate " + std::to_string(id) +
                           " lost its trajectory while it was exported");
      for (const PoseSeries& s : series) {
        std::visit(
            [&](const auto& values) {
              using T = typename std::decay_t<decltype(values)>::value_type;
              file.row(s.set, s.name,
                       std::is_same_v<T, float> ? H5T_NATIVE_FLOAT : H5T_NATIVE_DOUBLE, p,
                       values.data());
            },
            s.row(id, *t));
      }
    }
  }

  // GRIP's joint states: a two-finger gripper's (grasp target, finger 1, finger 2), each finger
  // at half grip's opening as the Panda's finger joints are; a hand's joints as they are.
  std::vector<double> joint_states(const TrajectoryRecord& t) const {
    if (!parallel_) return t.joints;
    std::vector<double> out;
    for (const double opening : t.joints) {
      out.insert(out.end(), {0.0, opening / 2, opening / 2});
    }
    return out;
  }

  // Columns [first, first + count) of every row of each frame's hand poses (row-major 3x4
  // [R | t]), then `last_row`: the tf matrices (0, 4, and 0 0 0 1), translations (3, 1) and
  // rotations (0, 3).
  static std::vector<double> pose_columns(const TrajectoryRecord& t, int first, int count,
                                          std::initializer_list<double> last_row) {
    std::vector<double> out;
    for (std::size_t k = 0; k + 11 < t.hand_poses.size(); k += 12) {
      for (int r = 0; r < 3; ++r) {
        const double* row = &t.hand_poses[k + 4 * static_cast<std::size_t>(r)];
        out.insert(out.end(), row + first, row + first + count);
      }
      out.insert(out.end(), last_row);
    }
    return out;
  }

  const DatasetReader& dataset_;
  const std::vector<CandidateRecord>& records_;
  const PairExport& pair_;
  ObjectRecord object_;
  GripperRecord gripper_;
  std::size_t frames_;
  std::size_t per_hand_;
  bool parallel_;
};

std::vector<PairExport> plan_pairs(const DatasetReader& dataset,
                                   const std::vector<CandidateRecord>& records,
                                   const std::filesystem::path& folder,
                                   const GripLayoutOptions& options) {
  const DatasetLayout& layout = dataset.layout();
  std::map<std::pair<std::uint32_t, std::uint32_t>, PairExport> pairs;
  for (std::uint64_t id = 0; id < layout.candidate_count; ++id) {
    if (layout.frame_slot[id] < 0 || records[id].status == Status::kPending) continue;
    if (!options.all && records[id].status != Status::kSuccess) continue;
    if (!dataset.has_trajectory(id)) continue;
    PairExport& pair = pairs[{layout.gripper[id], layout.object[id]}];
    pair.gripper = layout.gripper[id];
    pair.object = layout.object[id];
    pair.ids.push_back(id);
  }
  // Object names are unique in grip's plans; the index keeps two files apart if they are not.
  std::map<std::string, int> name_uses;
  std::vector<std::string> object_names;
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) {
    object_names.push_back(file_name_part(dataset.object(o).name));
    ++name_uses[object_names.back()];
  }
  std::vector<PairExport> out;
  for (auto& [key, pair] : pairs) {
    const ObjectRecord object = dataset.object(pair.object);
    std::string object_part = object_names[pair.object];
    if (name_uses[object_part] > 1) object_part.append("-").append(std::to_string(pair.object));
    std::string name = file_name_part(dataset.gripper(pair.gripper).name);
    name.append("_").append(object_part).append(object.soft ? "_soft.h5" : "_rigid.h5");
    pair.path = folder / name;
    out.push_back(std::move(pair));
  }
  return out;
}

}  // namespace

std::vector<GripLayoutFile> export_grip_layout(const DatasetReader& dataset,
                                               const std::filesystem::path& folder,
                                               const GripLayoutOptions& options) {
  const std::vector<CandidateRecord> records = dataset.candidates();
  const std::vector<PairExport> pairs = plan_pairs(dataset, records, folder, options);
  for (const PairExport& pair : pairs) {
    if (std::filesystem::exists(pair.path)) {
      throw DatasetError(pair.path.string() +
                         " exists already: export into an empty folder, or remove it first");
    }
  }
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw DatasetError(folder.string() + ": cannot create the folder (" + error.message() + ")");
  }
  std::vector<GripLayoutFile> files;
  for (const PairExport& pair : pairs) {
    std::filesystem::path partial = pair.path;
    partial += ".part";
    std::filesystem::remove(partial);
    try {
      PairWriter(dataset, records, pair).write(partial);
    } catch (...) {
      std::filesystem::remove(partial, error);
      throw;
    }
    std::filesystem::rename(partial, pair.path);
    files.push_back({pair.path, pair.ids.size()});
  }
  return files;
}

}  // namespace grip::io
