#pragma once
// The work behind each `grip` subcommand, one function per subcommand, called by cli.cpp.
// Each returns the process exit code.
#include <string>
#include <vector>

namespace grip::commands {

// grip inspect DATASET.h5 [--job]: provenance and summary of a dataset (src/app/commands/inspect.cpp).
int inspect(const std::string& dataset, bool show_job);

// grip asset prepare IN --out DIR --edge L: repair, tetrahedralize and write an object mesh
// (src/app/commands/asset.cpp).
struct AssetPrepareArgs {
  std::string input;           // surface mesh: .obj, .stl, .ply, .off
  std::string out_dir;         // receives <stem>.msh, <stem>.vtu, <stem>_surface.obj
  double edge_length = 0.0;    // target tet edge length (m)
  double alpha_ratio = 0.01;   // alpha-wrap fallback: alpha / bounding-box diagonal
  double offset_ratio = 1.0 / 3000.0;  // alpha-wrap fallback: offset / bounding-box diagonal
  unsigned seed = 0;           // tetrahedralization seed
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

// grip simulate SCENE.toml [--report FILE] [--trace]: run one scene file for its duration
// (src/app/commands/simulate.cpp).
struct SimulateArgs {
  std::string scene;
  std::string report;  // JSON report file; stdout when empty
  bool trace = false;  // add each step's time and centres of mass to the report
};
int simulate(const SimulateArgs& args);

}  // namespace grip::commands
