// grip asset prepare: read a surface mesh, repair it into a closed solid, tetrahedralize it
// and write the tet mesh (.msh, .vtu) and the repaired surface (.obj), with a report.
#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "src/geometry/mesh_io.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/repair.hpp"
#include "src/geometry/tetrahedralize.hpp"

namespace grip::commands {
namespace {

namespace fs = std::filesystem;
namespace geo = grip::geometry;
using Clock = std::chrono::steady_clock;

struct AssetPrepareArgs {
  std::string input;                   // surface mesh: .obj, .stl, .ply, .off
  std::string out_dir;                 // receives <stem>.msh, <stem>.vtu, <stem>_surface.obj
  double edge_length = 0.0;            // target tet edge length (m)
  double alpha_ratio = 0.01;           // alpha-wrap fallback: alpha / bounding-box diagonal
  double offset_ratio = 1.0 / 3000.0;  // alpha-wrap fallback: offset / bounding-box diagonal
  unsigned seed = 0;                   // tetrahedralization seed
  double max_tets = geometry::kMaxEstimatedTets;  // a finer mesh is refused before meshing
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The input surface repaired into a closed solid, with what was done to it.
geo::RepairedSurface repaired_surface(const geo::SurfaceMesh& raw, const AssetPrepareArgs& args,
                                      const std::string& source) {
  geo::RepairOptions repair_options;
  repair_options.alpha_ratio = args.alpha_ratio;
  repair_options.offset_ratio = args.offset_ratio;
  geo::RepairedSurface repaired = geo::repair_surface(raw, repair_options, source);
  std::printf("repair: %s\n", repaired.report.summary().c_str());
  if (repaired.report.alpha_wrapped) {
    const double diagonal = geo::bounding_box_diagonal(raw.vertices);
    std::printf("alpha wrap: alpha %.4g m, offset %.4g m (%.4g and %.4g of the %.4g m diagonal)\n",
                args.alpha_ratio * diagonal, args.offset_ratio * diagonal, args.alpha_ratio,
                args.offset_ratio, diagonal);
  }
  std::printf("repaired surface: %ld vertices, %ld triangles, volume %.6g m^3\n",
              static_cast<long>(repaired.mesh.vertices.rows()),
              static_cast<long>(repaired.mesh.triangles.rows()), repaired.report.volume);
  return repaired;
}

// The repaired surface's tet mesh, refused before meshing if it would be too fine.
geo::TetMesh tet_mesh(const geo::RepairedSurface& repaired, const AssetPrepareArgs& args,
                      const std::string& source) {
  const double surface_volume = repaired.report.volume;
  const double estimated_tets = geo::estimated_tet_count(surface_volume, args.edge_length);
  if (estimated_tets > args.max_tets) {
    throw std::invalid_argument(
        fmt::format("--edge {:g} m would make about {:.3g} tets for {}, more than the {:.0f} "
                    "allowed; use a larger --edge (or raise --max-tets)",
                    args.edge_length, estimated_tets, source, args.max_tets));
  }
  geo::TetOptions tet_options;
  tet_options.edge_length = args.edge_length;
  tet_options.seed = args.seed;
  geo::TetMesh tets = geo::tetrahedralize(repaired.mesh, tet_options, source);
  const geo::TetQuality quality = geo::tet_quality(tets);
  std::printf(
      "tet mesh: %ld vertices, %ld tets, dihedral angles %.2f to %.2f deg, "
      "%d inverted, %d below 5 deg\n",
      static_cast<long>(tets.vertices.rows()), static_cast<long>(tets.tets.rows()),
      quality.min_dihedral_deg, quality.max_dihedral_deg, quality.inverted_count,
      quality.sliver_count);
  std::printf("volume: tets %.6g m^3 vs repaired surface %.6g m^3 (relative difference %+.3f%%)\n",
              quality.total_volume, surface_volume,
              100.0 * (quality.total_volume / surface_volume - 1.0));
  return tets;
}

void write_asset(const fs::path& input, const AssetPrepareArgs& args, const geo::TetMesh& tets,
                 const geo::SurfaceMesh& surface) {
  const fs::path out(args.out_dir);
  std::error_code error;
  fs::create_directories(out, error);
  if (error) {
    throw std::runtime_error("cannot create output folder '" + out.string() +
                             "': " + error.message());
  }
  const std::string stem = input.stem().string();
  geo::write_msh(out / (stem + ".msh"), tets);
  geo::write_vtu(out / (stem + ".vtu"), tets);
  geo::write_obj(out / (stem + "_surface.obj"), surface);
  std::printf("wrote %s/%s.msh, %s.vtu, %s_surface.obj\n", out.string().c_str(), stem.c_str(),
              stem.c_str(), stem.c_str());
}

int asset_prepare(const AssetPrepareArgs& args) {
  const fs::path input(args.input);
  std::string source = "'";  // appended: GCC 12 warns falsely (-Wrestrict) on a + chain
  source += input.string();
  source += "'";
  if (!(std::isfinite(args.edge_length) && args.edge_length > 0.0)) {
    throw std::invalid_argument("--edge must be a positive length in metres");
  }
  if (!(args.alpha_ratio > 0.0) || !(args.offset_ratio > 0.0)) {
    throw std::invalid_argument("--alpha and --offset must be positive fractions of the size");
  }
  const auto start = Clock::now();

  const geo::SurfaceMesh raw = geo::read_surface_mesh(input);
  std::printf("%s: %ld vertices, %ld triangles\n", input.string().c_str(),
              static_cast<long>(raw.vertices.rows()), static_cast<long>(raw.triangles.rows()));
  if (const std::string warning = geo::metric_scale_warning(raw.vertices, input.string());
      !warning.empty()) {
    spdlog::warn("{}", warning);
  }
  const auto repair_start = Clock::now();
  const geo::RepairedSurface repaired = repaired_surface(raw, args, source);
  const double repair_seconds = seconds_since(repair_start);
  const auto tet_start = Clock::now();
  const geo::TetMesh tets = tet_mesh(repaired, args, source);
  const double tet_seconds = seconds_since(tet_start);
  write_asset(input, args, tets, repaired.mesh);
  std::printf("time: %.2f s (repair %.2f s, tetrahedralize %.2f s)\n", seconds_since(start),
              repair_seconds, tet_seconds);
  return 0;
}

}  // namespace

void declare_asset_prepare(cli::Command& asset) {
  auto args = std::make_shared<AssetPrepareArgs>();
  cli::Command prepare = asset.subcommand(
      "prepare",
      "Repair a surface mesh into a closed solid, tetrahedralize it, write .msh/.vtu/.obj");
  prepare.option("input", args->input, "Surface mesh (.obj, .stl, .ply, .off)").required();
  prepare.option("--out", args->out_dir, "Output folder")
      .required()
      .check(cli::Check::output_folder());
  prepare.option("--edge", args->edge_length, "Target tet edge length (m)")
      .required()
      .check(cli::Check::positive());
  prepare
      .option("--alpha", args->alpha_ratio,
              "Alpha-wrap fallback: alpha as a fraction of the bounding-box diagonal")
      .show_default()
      .check(cli::Check::positive());
  prepare
      .option("--offset", args->offset_ratio,
              "Alpha-wrap fallback: offset as a fraction of the bounding-box diagonal")
      .show_default()
      .check(cli::Check::positive());
  prepare
      .option("--max-tets", args->max_tets,
              "Refuse an --edge that would make more tets (estimated before meshing)")
      .show_default()
      .check(cli::Check::positive());
  prepare.option("--seed", args->seed, "Tetrahedralization seed")
      .show_default()
      .check(cli::Check::count());
  prepare.on_run([args] { return asset_prepare(*args); });
}

}  // namespace grip::commands
