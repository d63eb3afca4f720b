#include "farm/farm_object.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/objects/object_library.hpp"
#include "src/synth/object_spec.hpp"

namespace grip::farm {
namespace {

// SplitMix64: independent, well-mixed seeds from (job seed, object index, stream).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t derive(std::uint64_t job_seed, std::uint64_t index, std::uint64_t stream) {
  return mix(mix(mix(job_seed) ^ index) ^ stream);
}

// A row-major matrix as the record's flat array, and back.
template <typename T, typename Matrix>
std::vector<T> flat(const Matrix& m) {
  return std::vector<T>(m.data(), m.data() + m.size());
}

template <typename Matrix, typename T>
Matrix rows(const std::vector<T>& values) {
  const auto columns = Matrix::ColsAtCompileTime;
  return Eigen::Map<const Matrix>(values.data(), static_cast<Eigen::Index>(values.size() / columns),
                                  columns);
}

}  // namespace

std::vector<FarmObject> list_objects(const Job& job) {
  std::vector<FarmObject> objects;
  std::map<std::string, int> stems;  // mesh files of the same stem get "-1", "-2", ...
  std::map<std::string, int> per_category;
  for (const ObjectGroup& group : job.objects) {
    auto add = [&](FarmObject object) {
      const std::uint64_t index = objects.size();
      object.seed = derive(job.seed, index, 1);
      object.soft = group.soft;
      object.tet_edge = group.tet_edge;
      object.tet_edge_at = group.tet_edge_at;
      object.tet_growth = group.tet_growth;
      object.tets_across = group.tets_across;
      object.max_tets = job.max_tets;
      object.mesh_scale = group.mesh_scale;
      object.material = group.randomize ? objects::randomize_material(job.randomization,
                                                                      derive(job.seed, index, 2))
                                        : group.material;
      objects.push_back(std::move(object));
    };
    if (!group.category.empty()) {
      for (int k = 0; k < group.count; ++k) {
        FarmObject object;
        const int n = per_category[group.category]++;
        object.name = group.category + "-" + std::to_string(n);
        object.category = group.category;
        object.shape_seed = derive(job.seed, objects.size(), 0);
        add(std::move(object));
      }
    } else {
      for (const std::filesystem::path& mesh : group.meshes) {
        FarmObject object;
        const std::string stem = mesh.stem().string();
        const int n = stems[stem]++;
        object.name = n == 0 ? stem : stem + "-" + std::to_string(n);
        object.category = "mesh";
        object.mesh = mesh;
        add(std::move(object));
      }
    }
  }
  return objects;
}

io::ObjectRecord prepare_object(const FarmObject& object) {
  geometry::SurfaceMesh surface =
      object.category == "mesh" ? synth::load_object(object.mesh.string(), 0, object.mesh_scale)
                                : synth::load_object(object.category, object.shape_seed);
  surface.vertices *= object.material.scale;

  io::ObjectRecord record;
  record.name = object.name;
  record.category = object.category;
  record.scale = object.material.scale;
  record.soft = object.soft;
  record.material = {object.material.youngs_modulus, object.material.poisson_ratio,
                     object.material.density, object.material.friction};
  if (object.soft) {
    geometry::TetOptions options;
    options.edge_length =
        synth::object_tet_edge(object.category, object.shape_seed, object.material.scale,
                               object.tet_edge, object.tets_across);
    options.interior_growth = object.tet_growth;
    const double estimate = geometry::estimated_tet_count(
        std::abs(geometry::surface_volume(surface)), options.edge_length);
    if (estimate > object.max_tets) {
      char message[512];
      std::snprintf(message, sizeof message,
                    "%s: [[objects]] tet_edge: an edge of %g m would make about %.3g tets for "
                    "'%s', more than the %.0f allowed ([farm] max_tets); use a larger tet_edge",
                    object.tet_edge_at.c_str(), options.edge_length, estimate, object.name.c_str(),
                    object.max_tets);
      throw std::invalid_argument(message);
    }
    const geometry::TetMesh tets = geometry::tetrahedralize(surface, options, object.name);
    Eigen::VectorXi surface_to_tet;
    const geometry::SurfaceMesh boundary = geometry::boundary_surface(tets, &surface_to_tet);
    record.vertices = flat<double>(tets.vertices);
    for (Eigen::Index f = 0; f < boundary.triangles.rows(); ++f) {
      for (int c = 0; c < 3; ++c)
        record.triangles.push_back(surface_to_tet[boundary.triangles(f, c)]);
    }
    record.tets = flat<std::int32_t>(tets.tets);
  } else {
    record.vertices = flat<double>(surface.vertices);
    record.triangles = flat<std::int32_t>(surface.triangles);
  }
  return record;
}

trial::TrialObject trial_object(const io::ObjectRecord& record) {
  trial::TrialObject object;
  object.name = record.name;
  object.material.density = record.material.density;
  object.material.youngs = record.material.young_modulus;
  object.material.poisson = record.material.poisson_ratio;
  object.material.friction = record.material.friction;
  const geometry::Vertices vertices = rows<geometry::Vertices>(record.vertices);
  if (record.soft) {
    geometry::TetMesh tets{vertices, rows<geometry::Tetrahedra>(record.tets)};
    object.surface = geometry::boundary_surface(tets);
    object.tets = std::move(tets);
  } else {
    object.surface = {vertices, rows<geometry::Triangles>(record.triangles)};
  }
  return object;
}

}  // namespace grip::farm
