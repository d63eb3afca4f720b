#pragma once
// The objects of a job, one entry per object of the dataset: which shape (a procedural
// category's seeded shape or a mesh file), which material and scale (drawn from the job's
// ranges), soft or rigid; and their preparation into the dataset's object record, from which
// every rank rebuilds the trial's object without redoing the geometry.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "farm/job.hpp"
#include "io/object_record.hpp"
#include "src/trial/trial_object.hpp"

namespace grip::farm {

struct FarmObject {
  std::string name;      // "cylinder-3": category and index in its entry; a mesh file's stem
  std::string category;  // the procedural category, or "mesh"
  std::filesystem::path mesh;
  std::uint64_t shape_seed = 0;  // a category's shape
  std::uint64_t seed = 0;        // the object's own stream (material, synthesis, trials)
  bool soft = false;
  double tet_edge = 0.008;  // m, soft objects
  std::string tet_edge_at;  // "job.toml:LINE" of its entry's tet_edge
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // TetOptions::interior_growth
  double tets_across = objects::kDefaultTetsAcross;         // ObjectGroup::tets_across
  double max_tets = geometry::kMaxEstimatedTets;            // the job's [farm] max_tets
  double mesh_scale = 1.0;                                  // multiplies a mesh file's coordinates
  objects::ObjectMaterial material;  // material.scale multiplies every length
};

// Every object of the job, in job order (entries in order, then count or sorted files).
// Seeds come from the job's seed and the object's position only, so a job reads the same on
// every rank.
std::vector<FarmObject> list_objects(const Job& job);

// The object's closed surface (repaired, scaled) and, when soft, its tet mesh, as the
// dataset's record. Deterministic. Throws std::invalid_argument naming the object when its
// geometry cannot be prepared.
io::ObjectRecord prepare_object(const FarmObject& object);

// The trial's object from its record (a soft object's surface is its tets' boundary).
trial::TrialObject trial_object(const io::ObjectRecord& record);

}  // namespace grip::farm
