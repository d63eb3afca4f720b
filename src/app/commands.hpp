#pragma once
// The work behind each `grip` subcommand, one function per subcommand, called by cli.cpp.
// Each returns the process exit code.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "src/geometry/tetrahedralize.hpp"

namespace grip::commands {

// grip inspect DATASET.h5 [--job]: provenance and summary of a dataset
// (src/app/commands/inspect.cpp).
int inspect(const std::string& dataset, bool show_job);

// grip asset prepare IN --out DIR --edge L: repair, tetrahedralize and write an object mesh
// (src/app/commands/asset.cpp).
struct AssetPrepareArgs {
  std::string input;                   // surface mesh: .obj, .stl, .ply, .off
  std::string out_dir;                 // receives <stem>.msh, <stem>.vtu, <stem>_surface.obj
  double edge_length = 0.0;            // target tet edge length (m)
  double alpha_ratio = 0.01;           // alpha-wrap fallback: alpha / bounding-box diagonal
  double offset_ratio = 1.0 / 3000.0;  // alpha-wrap fallback: offset / bounding-box diagonal
  unsigned seed = 0;                   // tetrahedralization seed
  double max_tets = geometry::kMaxEstimatedTets;  // a finer mesh is refused before meshing
};
int asset_prepare(const AssetPrepareArgs& args);

// grip ccd-bench --type vf|ee FILE.csv | --write-hard DIR: additive CCD scored on a CCD
// benchmark file, or the generated hard query set written in that format
// (src/app/commands/ccd_bench.cpp).
struct CcdBenchArgs {
  std::string file;            // rational CSV query file (Wang et al. 2021 format)
  std::string type;            // "vf" (vertex-face) or "ee" (edge-edge)
  std::string write_hard_dir;  // if set: write hard-vertex-face.csv and hard-edge-edge.csv here
};
int ccd_bench(const CcdBenchArgs& args);

// grip asset gallery --out DIR: every object category (the seed-0 shape) and every gripper
// (open and closed) as .obj meshes, the fin-ray finger's tet mesh, and freshly generated
// LEAP-style hand packages (src/app/commands/gallery.cpp).
struct AssetGalleryArgs {
  std::string out_dir;  // receives objects/, grippers/ and hands/
};
int asset_gallery(const AssetGalleryArgs& args);

// grip simulate SCENE.toml... [--threads T] [--report FILE] [--trace]: run scene files for their
// durations as one batch (src/app/commands/simulate.cpp).
struct SimulateArgs {
  std::vector<std::string> scenes;
  int threads = 0;     // 0: all cores
  std::string report;  // JSON report file; stdout when empty
  bool trace = false;  // add each step's time and centres of mass to the report
  double max_tets = geometry::kMaxEstimatedTets;  // an FEM body of more tets is refused
};
int simulate(const SimulateArgs& args);

// grip bench batch --scene S.toml [--envs 1,2,4,...] [--threads T] [--jitter SEED]: N copies
// of a scene one after another and as one batch (src/app/commands/bench_batch.cpp).
struct BenchBatchArgs {
  std::string scene;
  std::vector<int> envs{1, 2, 4, 8, 16, 32, 64};
  int threads = 0;           // 0: all cores
  std::int64_t jitter = -1;  // seed; < 0: no jitter
};
int bench_batch(const BenchBatchArgs& args);

// grip synth --object SPEC --gripper fin-ray|leap|parallel-jaw [--bimanual] --count N --seed S
// --out FILE: candidate grasps written to a candidate file (src/app/commands/synth.cpp).
struct SynthArgs {
  std::string object;   // an object category name or a surface mesh file
  double scale = 1.0;   // multiplies a mesh file's coordinates
  std::string gripper;  // fin-ray, parallel-jaw or leap
  bool bimanual = false;
  int count = 0;
  std::uint64_t seed = 0;
  std::string out;       // candidate file (docs/synthesis.md)
  int steps = 1500;      // annealing steps per hand attempt
  double d_hat = 1e-3;   // m, IPC barrier activation distance
  double margin = 5e-4;  // m, clearance kept beyond d_hat
};
int synth(const SynthArgs& args);

// grip trial --candidates FILE [--object SPEC] [--seed S] [--scale X] [--gripper G] --index
// I|A-B [--report FILE] [--vtk DIR] [--soft] [--compare-solo]: grasp trials of candidates as
// one batch (src/app/commands/trial.cpp, docs/trial.md). The object and gripper come from the
// candidate file; given on the command line they must agree with it.
struct TrialArgs {
  std::optional<std::string> object;  // a category name (shape from the seed) or a mesh file
  std::optional<double> scale;        // multiplies a mesh file's coordinates
  std::optional<std::uint64_t> seed;  // the category's shape, as given to grip synth
  bool soft = false;                  // FEM object (tetrahedralized) instead of one affine body
  double tet_edge = 0.008;            // m, target tet edge length of a soft object
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // TetOptions::interior_growth
  double max_tets = geometry::kMaxEstimatedTets;            // a finer soft object is refused
  double density = 1000.0;                                  // kg/m^3
  double youngs = 1e6;                                      // Pa, soft objects
  double poisson = 0.4;                                     // soft objects
  double friction = 3.5;               // the object's mu (a fin-ray pad's pairs use the pad's 3.5)
  std::optional<std::string> gripper;  // fin-ray, parallel-jaw or leap
  std::string candidates;              // candidate file (docs/synthesis.md)
  bool bimanual = false;               // the file's candidates are bimanual (two grippers)
  std::string index = "0";             // one candidate "I" or a range "A-B", run as one batch
  std::string report;                  // JSON report file; stdout when empty
  std::string vtk;                     // folder for per-candidate VTK series; none when empty
  int threads = 0;                     // 0: all cores
  double squeeze_speed = 0.01;         // m/s per finger, closing and servoing
  double grip_force = 50.0;            // N per finger
  bool compare_solo = false;           // also run each candidate alone: speedup and identity
  // The fin-ray finger's mesh (grippers::FinRayOptions layers and edge_length); unset: its
  // defaults. Refused for other grippers.
  std::optional<int> finger_layers;
  std::optional<double> finger_edge;  // m
};
int trial(const TrialArgs& args);

// grip farm JOB.toml [--output FILE] [--resume] [--threads T] [--batch B]: the dataset farm,
// under mpirun or as one process (src/app/commands/farm.cpp, docs/farm.md).
struct FarmArgs {
  std::string job;     // job file (docs/job-format.md)
  std::string output;  // the dataset; empty: the job's [job] output
  bool resume = false;
  int threads = 0;     // per rank; 0: the node's cores shared by its ranks
  int batch = 0;       // candidates per work unit; 0: the job's [farm] batch, else 4 per thread
  std::string report;  // JSON summary of the run (rank 0); none when empty
  std::vector<std::string> petsc_options;  // after a lone `--`: the job's PETSc groups'
};
int farm(const FarmArgs& args);

// grip bench scaling JOB.toml [--ranks 1,2] [--envs 4,8] [--threads T] [--repeats N] --out DIR:
// the job under mpirun at each rank and batch size; trials per second and speedup as a table
// and a plot (bench/scaling/, docs/farm.md).
struct BenchScalingArgs {
  std::string job;
  std::vector<int> ranks{1, 2};
  std::vector<int> envs{0};  // candidates per batch; 0: the farm's default
  int threads = 0;           // per rank; 0: the farm's default (the node's cores shared)
  int repeats = 3;           // runs per setting; the table reports the median
  std::string out = "out/scaling";
};
int bench_scaling(const BenchScalingArgs& args);

// grip bench scale [--costs FILE] [--ranks 64,...] [--measure 1,2,3] [--validate JOB]
// [--what-if ...] [--out DIR]: the farm's protocol simulated from measured costs to thousands
// of ranks, checked against real runs (bench/scale/, docs/farm.md).
struct BenchScaleArgs {
  std::string costs = "docs/results/trial/trial.csv";  // grip bench trial's trial.csv or a dataset
  std::vector<std::string> grippers{"fin-ray"};
  std::uint64_t objects = 1200;
  std::uint64_t candidates = 100000;
  double soft_fraction = 0.5;
  std::uint64_t seed = 1;
  std::vector<int> ranks{64, 128, 256, 512, 1024, 2048, 4096};
  int batch = 4;
  int round_batches = 4;     // the rounds what-if's work units per rank per round
  std::vector<int> measure;  // rank counts for the commit probe; empty: the constants
  std::string validate;      // a job run at validate_ranks and compared
  std::vector<int> validate_ranks{1, 2, 3};
  std::vector<std::string> what_if;  // rounds, heaviest-first, round-batches=N, batch=N
  // The model's constants where no measurement replaces them (docs/farm.md gives their source).
  double unit_commit_latency = 0.00174;
  double unit_commit_bandwidth = 443e6;
  double journal_line = 0.000366;
  double commit_latency = 0.0348;
  double commit_per_log2 = 0.00263;
  double commit_bandwidth = 340e6;
  double claim_latency = 2.59e-6;
  double claim_service = 0.864e-6;
  double startup = 0.794;
  double prepare_rigid = 0.0501;
  double prepare_soft = 0.0501;
  double synthesis = 0.0;
  double scene_build = 0.0;
  double bytes_per_candidate = 400;
  double broadcast_per_log2 = 5e-6;
  std::string out = "out/bench-scale";
};
int bench_scale(const BenchScaleArgs& args);

// grip bench scale-probe --out FILE --folder DIR, under mpirun: the claim and commit costs
// grip bench scale --measure fits its model to (bench/scale/commit_probe.hpp).
struct BenchScaleProbeArgs {
  std::string out;
  std::string folder;
};
int bench_scale_probe(const BenchScaleProbeArgs& args);

// grip bench linear [--cells 0.01,0.006,...] [--repeats N] [-- PETSc options]: CHOLMOD against
// PETSc's KSP on Newton systems of growing size, on the ranks it runs with (bench/linear/,
// docs/linear-solvers.md).
struct BenchLinearArgs {
  std::string system = "bimanual-trial";  // or "squeeze" (bench/linear/linear_benchmark.hpp)
  std::vector<double> cells{0.01, 0.006, 0.004, 0.003, 0.0025};  // tet cell sizes (m)
  int repeats = 5;
  std::vector<std::string> petsc_options;  // after a lone `--`
};
int bench_linear(const BenchLinearArgs& args);

// grip bench accuracy [--scenes ...] [--sweeps ...] [--threads T] [--repeats N] [--out DIR]:
// work-precision of the solver's settings on the standard trial scenes against a tight
// reference run (bench/accuracy/, docs/results.md).
struct BenchAccuracyArgs {
  std::vector<std::string> scenes;  // empty: every standard scene
  std::vector<std::string> sweeps;  // settings to sweep; empty: all
  int threads = 0;                  // 0: all cores
  int repeats = 1;                  // runs per setting; the wall time is their median
  std::string out = "out/accuracy";
};
int bench_accuracy(const BenchAccuracyArgs& args);

// grip bench hard [--cases ...] [--threads T] [--out DIR]: the hard-case suite, a pass/fail per
// invariant and statistics per case; non-zero exit when any case fails an invariant, its
// expected solver outcome or its physical check (bench/hard/, docs/results.md).
struct BenchHardArgs {
  std::vector<std::string> cases;  // empty: every case
  int threads = 0;                 // 0: all cores
  std::string out = "out/hard";
};
int bench_hard(const BenchHardArgs& args);

// grip bench model [--repeats N] [--threads T] [--out DIR]: what modelling only what a scene
// needs saves, in time and error (bench/model/, docs/results.md).
struct BenchModelArgs {
  int repeats = 5;  // runs per variant; the table reports the median
  int threads = 1;
  std::string out = "out/model";
};
int bench_model(const BenchModelArgs& args);

// grip bench robustness [--grippers ...] [--categories ...] [--seeds N] [--candidates N]
// [--rigid] [--soft] [--threads T] [--out DIR]: solver failures on synthesized grasps over
// every object category; the counts are the result, so the exit code is 0 unless the inputs
// are bad (bench/robustness/, docs/results.md).
struct BenchRobustnessArgs {
  std::vector<std::string> grippers;    // empty: parallel-jaw, fin-ray, leap
  std::vector<std::string> categories;  // empty: every procedural category
  int seeds = 0;                        // shapes per category; 0: each gripper's default
  int candidates = 0;                   // per (object, gripper); 0: each gripper's default
  bool rigid = false;                   // only rigid objects (with soft, or neither: both)
  bool soft = false;                    // only soft objects
  int threads = 0;                      // 0: all cores
  std::string out = "out/robustness";
};
int bench_robustness(const BenchRobustnessArgs& args);

struct BenchLabelsArgs {
  std::vector<std::string> arms;        // "gripper:rigid|soft"; empty: the benchmark's four
  std::vector<std::string> categories;  // empty: box, cylinder, capsule, bottle
  int seeds = 2;                        // shapes per category
  int candidates = 4;                   // per shape
  int threads = 0;                      // 0: all cores
  std::string models = "coarse";        // coarse | production (LabelsOptions)
  // What the reference refines: any of dt, newton_tol, friction_lag; empty: all three.
  std::vector<std::string> refine;
  int dt_divisor = 2;               // what refining dt divides it by
  double newton_tol = 0.0;          // the defaults' Newton tolerance; 0: the trial's
  int friction_lag_iterations = 0;  // the defaults' friction lag iterations; 0: the trial's
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // production soft objects
  std::string out = "out/labels";
};
int bench_labels(const BenchLabelsArgs& args);

// grip bench peer [--gripper G] [--categories ...] [--seeds N] [--candidates N] [--threads N]
// [--out DIR] [--vtk DIR]: the same parallel-jaw or LEAP-hand candidates validated by grip and
// by MuJoCo (bench/peer/, docs/results.md).
struct BenchPeerArgs {
  std::string gripper = "parallel-jaw";  // or leap
  std::vector<std::string> categories;   // empty: box, cylinder, capsule, bottle, sphere, ellipsoid
  int seeds = 4;                         // shapes per category
  int candidates = 9;                    // per shape
  int threads = 1;                       // grip's trial
  std::string out = "out/peer";
  std::string vtk;  // the hand's disagreement examples as VTK; empty: none
};
int bench_peer(const BenchPeerArgs& args);

// grip bench trial [--arms ...] [--categories ...] [--candidates N] [--repeats N]
// [--no-reference] [--out DIR]: what one grasp trial costs per gripper x object model, by solver
// stage, one trial at a time on one thread (bench/trial/, docs/results.md).
struct BenchTrialArgs {
  std::vector<std::string> arms;        // "gripper:rigid|soft"; empty: the benchmark's five
  std::vector<std::string> categories;  // empty: box, cylinder, capsule, bottle
  int candidates = 0;                   // per arm; 0: the arm's default
  int repeats = 3;                      // runs of each candidate at the defaults (median)
  bool no_reference = false;            // skip the runs at the reference
  std::string models = "production";    // production | coarse (TrialBenchOptions)
  std::string out = "out/bench-trial";
};
int bench_trial(const BenchTrialArgs& args);

}  // namespace grip::commands
