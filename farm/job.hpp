#pragma once
// A farm job file (TOML, docs/job-format.md) read strictly: which objects (procedural
// categories or mesh files) each gripper grasps, how many candidates per object, the solver,
// trial and synthesis settings, what each candidate records, and the work unit size.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/provenance.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/objects/domain_randomization.hpp"
#include "src/objects/object_library.hpp"
#include "src/synth/synthesis_settings.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::farm {

// One [[objects]] entry: `count` shapes of a procedural category, or every mesh file a path
// or glob names.
struct ObjectGroup {
  std::string category;                       // a procedural category; empty for mesh files
  std::vector<std::filesystem::path> meshes;  // resolved, sorted; empty for a category
  int count = 1;                              // shapes drawn from the category
  bool soft = false;                          // FEM (tetrahedralized) instead of one affine body
  double tet_edge = 0.008;                    // m, soft objects' target tet edge length
  std::string tet_edge_at;                    // "job.toml:LINE" of tet_edge (or of the entry)
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // TetOptions::interior_growth
  // A category's tets: at most its thinnest part (a wall) over this many edges.
  double tets_across = objects::kDefaultTetsAcross;
  double mesh_scale = 1.0;  // multiplies a mesh file's coordinates (units)
  // Draw scale and material from the job's ranges; otherwise use `material` as given.
  bool randomize = true;
  objects::ObjectMaterial material;

  // The objects the entry makes: `count`, or one per mesh file.
  std::uint64_t object_count() const {
    return category.empty() ? meshes.size() : static_cast<std::uint64_t>(count);
  }
};

// One [[grippers]] entry.
struct GripperSetting {
  // A built-in gripper ([[grippers]] name) or one read from its description file (description).
  grippers::GripperType type = grippers::gripper_type(grippers::GripperKind::kParallelJaw);
  bool bimanual = false;  // two grippers of the kind (a hand: a right and a left one)
  int candidates = 16;    // synthesized per object
};

struct PetscGroupSetting {
  int group_ranks = 0;
  int groups = 1;
  // A trial's systems go to a group when CHOLMOD's factor of its model's contact-free pattern
  // would take min_factor_mib or more (Model::contact_free_factor_bytes), or, if min_dofs > 0,
  // when the model has min_dofs DOFs or more.
  double min_factor_mib = kDefaultMinFactorMib;
  int min_dofs = 0;
  std::string location;

  // A memory budget (docs/linear-solvers.md, "Which systems go to PETSc"): a rank of a 24 GB,
  // 2-core node has 12 GiB, and keeps up to 2 x threads environments in flight, each with its
  // own factor. Neither this nor the DOFs tells where PETSc gets faster: that depends on the
  // object's shape.
  static constexpr double kDefaultMinFactorMib = 2048.0;
  int ranks() const { return group_ranks * groups; }
  std::size_t min_factor_bytes() const {
    return static_cast<std::size_t>(min_factor_mib * 1024 * 1024);
  }
};

struct Job {
  std::filesystem::path file;  // as given
  std::string text;            // verbatim (the dataset's provenance)
  std::string name;
  std::uint64_t seed = 0;
  std::filesystem::path output;  // the dataset; relative paths are taken from the working folder
  std::vector<ObjectGroup> objects;
  std::vector<GripperSetting> grippers;
  objects::RandomizationRanges randomization;
  trial::TrialParameters trial;        // trial.sim holds the [physics] settings
  synth::SynthesisSettings synthesis;  // [synthesis]
  bool record_frames = true;           // every candidate's trajectory
  bool record_stress = true;  // soft objects' and soft fingers' von Mises stress, settled grasp
  bool full_trials = false;   // run decided trials to the end (trial::TrialRunOptions)
  // [farm] batch: candidates per work unit; 0: 4 per worker thread.
  int work_unit_size = 0;
  // [farm] max_candidates: the most candidates (objects x candidates per gripper, summed over
  // the grippers) the job may plan; a larger job is refused when it is read, saying what it
  // would need. Raised in the job file by whoever means it.
  std::uint64_t max_candidates = kDefaultMaxCandidates;

  static constexpr std::uint64_t kDefaultMaxCandidates = 1'000'000;
  // [farm] max_tets: a soft object whose tet_edge would make more tets (estimated before
  // meshing) is refused while planning.
  double max_tets = geometry::kMaxEstimatedTets;
  // [farm] petsc_group_ranks, petsc_groups, petsc_min_factor_mib, petsc_min_dofs: petsc_groups
  // groups of petsc_group_ranks ranks each solve the Newton systems of their leader's trials
  // too big for CHOLMOD through PETSc (docs/farm.md, "PETSc groups"); 0 ranks: none, every
  // system is CHOLMOD's. A run with fewer ranks than the groups need is refused before any
  // work, at location ("FILE:LINE" of petsc_group_ranks).
  PetscGroupSetting petsc;

  // The objects of every [[objects]] entry.
  std::uint64_t object_count() const;
  // Objects x candidates per gripper, summed over the grippers: what planning synthesizes.
  std::uint64_t candidate_count() const;
};

// The job file's text. Throws config::ConfigError naming the file when it cannot be read.
std::string read_job_text(const std::filesystem::path& file);

// Reads and checks a job file. Throws config::ConfigError ("FILE:LINE: ...") naming the key
// and what is allowed, for anything wrong, including a mesh path or glob that matches nothing.
Job load_job(const std::filesystem::path& file);
// The same from text already read (every rank parses rank 0's copy of the file).
Job parse_job(std::string text, const std::filesystem::path& file);

// The resolved settings, as the dataset's provenance lists them ("physics.dt" = "0.01", ...).
std::vector<io::Parameter> resolved_parameters(const Job& job);

}  // namespace grip::farm
