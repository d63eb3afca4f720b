#include "src/synth/object_spec.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/repair.hpp"
#include "src/objects/object_library.hpp"

namespace grip::synth {
namespace {

// The category a spec names; none for a mesh file's path.
std::optional<objects::ObjectCategory> category_of(const std::string& spec) {
  for (const objects::ObjectCategory category : objects::all_object_categories()) {
    if (objects::category_name(category) == spec) return category;
  }
  return std::nullopt;
}

}  // namespace

geometry::SurfaceMesh load_object(const std::string& spec, std::uint64_t seed, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    throw std::invalid_argument("--scale must be a positive factor (got " + std::to_string(scale) +
                                ")");
  }
  if (const auto category = category_of(spec)) {
    return objects::generate_surface(objects::sample_shape(*category, seed));
  }
  if (std::filesystem::is_directory(spec)) {
    throw std::invalid_argument("--object '" + spec + "' is a directory, not a mesh file");
  }
  if (!std::filesystem::is_regular_file(spec)) {
    std::string names;
    for (const objects::ObjectCategory category : objects::all_object_categories()) {
      names += (names.empty() ? "" : ", ") + std::string(objects::category_name(category));
    }
    throw std::invalid_argument("--object '" + spec + "' is neither an object category (" + names +
                                ") nor an existing mesh file (.obj, .stl, .ply, .off)");
  }
  geometry::SurfaceMesh mesh = geometry::read_surface_mesh(spec);
  mesh.vertices *= scale;
  return geometry::repair_surface(mesh, {}, spec).mesh;
}

double object_tet_edge(const std::string& spec, std::uint64_t seed, double category_scale,
                       double requested, double tets_across) {
  const auto category = category_of(spec);
  return category ? objects::tet_edge_for(objects::sample_shape(*category, seed), category_scale,
                                          requested, tets_across)
                  : requested;
}

std::string object_file_hash(const std::string& spec) {
  if (category_of(spec)) return "";
  std::ifstream in(spec, std::ios::binary);
  if (!in) throw std::invalid_argument("--object '" + spec + "': cannot read the mesh file");
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a, 64 bits
  for (std::istreambuf_iterator<char> c(in), end; c != end; ++c) {
    hash = (hash ^ static_cast<unsigned char>(*c)) * 1099511628211ULL;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, hash);
  return text;
}

}  // namespace grip::synth
