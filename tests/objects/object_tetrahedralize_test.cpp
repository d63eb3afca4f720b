// Every procedural category tetrahedralizes with no inverted tet, no sliver (minimum dihedral
// angle at least kMinDihedralDeg) and a tet volume close to its surface's volume: a small
// member of each category, and sampled members of a few seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/objects/object_library.hpp"

namespace grip::objects {
namespace {

// Perturbation and exudation aim at TetOptions::sliver_bound_deg (12 degrees); the bound
// promised is lower because a few tets between protected sharp features (vertices that
// perturbation may not move) can stay under the aim. Measured minima: 10.91 (sampled mug 1,
// on its handle's blend) to 13.81 degrees.
constexpr double kMinDihedralDeg = 10.0;
// Relative volume difference. Mesh_3 keeps the surface within facet_distance = 0.1 edge of
// the input, inscribed in curved parts: the volume falls short by up to about
// area * 0.1 * edge / volume, 2 to 6 percent for round solids at edge = diagonal / 15, and
// is exact for flat-faced shapes.
constexpr double kVolumeTolerance = 0.07;

// The sizing thinnest_feature recommends (half of it), capped at a fifteenth of the diagonal.
// A coarser edge, e.g. two thirds of a bottle neck's diameter, leaves the four vertices of a
// tet on one rim circle, a sliver no vertex move can undo.
double edge_length(const ObjectShape& shape, const geometry::SurfaceMesh& surface) {
  return std::min(thinnest_feature(shape) / 2.0,
                  geometry::bounding_box_diagonal(surface.vertices) / 15.0);
}

void expect_good_tets(const ObjectShape& shape, const std::string& name) {
  const geometry::SurfaceMesh surface = generate_surface(shape, 32);
  geometry::TetOptions options;
  options.edge_length = edge_length(shape, surface);
  const geometry::TetMesh mesh = geometry::tetrahedralize(surface, options, name);
  const geometry::TetQuality quality = geometry::tet_quality(mesh, kMinDihedralDeg);
  const double relative = quality.total_volume / geometry::surface_volume(surface) - 1.0;
  std::printf("%-12s edge %.4f m %6ld vertices %7ld tets  min dihedral %5.2f deg  volume %+.4f\n",
              name.c_str(), options.edge_length, static_cast<long>(mesh.vertices.rows()),
              static_cast<long>(mesh.tets.rows()), quality.min_dihedral_deg, relative);
  EXPECT_EQ(quality.inverted_count, 0) << name;
  EXPECT_EQ(quality.sliver_count, 0) << name;
  EXPECT_GE(quality.min_dihedral_deg, kMinDihedralDeg) << name;
  EXPECT_LT(std::abs(relative), kVolumeTolerance) << name;
}

// Small members of each category (a few thousand tets each at most) to keep the test fast.
std::vector<ObjectShape> compact_shapes() {
  return {{ObjectCategory::kBox, {0.05, 0.04, 0.03}},
          {ObjectCategory::kCylinder, {0.02, 0.05}},
          {ObjectCategory::kSphere, {0.03}},
          {ObjectCategory::kEllipsoid, {0.04, 0.03, 0.02}},
          {ObjectCategory::kCapsule, {0.02, 0.03}},
          {ObjectCategory::kCone, {0.03, 0.05}},
          {ObjectCategory::kTorus, {0.03, 0.012}},
          {ObjectCategory::kBottle, {0.025, 0.08, 0.015, 0.02}},
          {ObjectCategory::kCup, {0.03, 0.06, 0.008, 0.01}},
          {ObjectCategory::kMug, {0.035, 0.08, 0.008, 0.01, 0.018, 0.007}},
          {ObjectCategory::kBowl, {0.05, 0.008}},
          {ObjectCategory::kPlate, {0.08, 0.06, 0.012}},
          {ObjectCategory::kBar, {0.2, 0.03, 0.03}},
          {ObjectCategory::kRod, {0.015, 0.25}}};
}

TEST(ObjectsObjectTetrahedralizeTest, EveryCategoryMeshesWithoutInvertedOrSliverTets) {
  const auto shapes = compact_shapes();
  ASSERT_EQ(shapes.size(), all_object_categories().size()) << "one shape per category";
  for (const ObjectShape& shape : shapes) {
    expect_good_tets(shape, std::string(category_name(shape.category)));
  }
}

// Sampled shapes cover the parameter ranges: thin necks and cone tops, a torus whose
// bounding-box centre lies in its hole, walls a few millimetres thick, a mug's handle seam.
TEST(ObjectsObjectTetrahedralizeTest, SampledShapesMeshWithoutInvertedOrSliverTets) {
  for (const ObjectCategory category : all_object_categories()) {
    for (const std::uint64_t seed : {1, 2}) {
      expect_good_tets(sample_shape(category, seed),
                       std::string(category_name(category)) + "/" + std::to_string(seed));
    }
  }
}

// The mug's handle seam at the library's default surface resolution (the farm's): seeds whose
// seam once left slivers (seed 5: 2.05 degrees, before boolean_union collapsed needles of
// aspect 20; seed 2: 6.47 degrees at aspect 10).
TEST(ObjectsObjectTetrahedralizeTest, MugHandleSeamsMeshWithoutSlivers) {
  for (const std::uint64_t seed : {2, 5}) {
    const ObjectShape shape = sample_shape(ObjectCategory::kMug, seed);
    const geometry::SurfaceMesh surface = generate_surface(shape);
    geometry::TetOptions options;
    options.edge_length = edge_length(shape, surface);
    const std::string name = "mug/" + std::to_string(seed);
    const geometry::TetMesh mesh = geometry::tetrahedralize(surface, options, name);
    const geometry::TetQuality quality = geometry::tet_quality(mesh, kMinDihedralDeg);
    std::printf("%-12s edge %.4f m %7ld tets  min dihedral %5.2f deg\n", name.c_str(),
                options.edge_length, static_cast<long>(mesh.tets.rows()), quality.min_dihedral_deg);
    EXPECT_EQ(quality.inverted_count, 0) << name;
    EXPECT_GE(quality.min_dihedral_deg, kMinDihedralDeg) << name;
  }
}

// A job's one tet edge (8 mm by default) over thin-walled objects: meshed at 8 mm these
// sampled shapes had minimum dihedral angles of 0.8 (mug/1), 9.1 (cup/0) and 5.9 (bowl/6)
// degrees; tet_edge_for meshes them at half their thinnest part instead.
TEST(ObjectsObjectTetrahedralizeTest, ThinWallsAreMeshedFinerThanTheJobsEdge) {
  const double job_edge = 0.008;
  for (const auto& [category, seed] :
       {std::pair{ObjectCategory::kMug, 1}, std::pair{ObjectCategory::kCup, 0},
        std::pair{ObjectCategory::kBowl, 6}}) {
    const ObjectShape shape = sample_shape(category, seed);
    const std::string name = std::string(category_name(category)) + "/" + std::to_string(seed);
    geometry::TetOptions options;
    options.edge_length = tet_edge_for(shape, 1.0, job_edge);
    EXPECT_NEAR(options.edge_length, thinnest_feature(shape) / 2.0, 1e-15) << name;
    const geometry::TetMesh mesh = geometry::tetrahedralize(generate_surface(shape), options, name);
    const geometry::TetQuality quality = geometry::tet_quality(mesh, kMinDihedralDeg);
    std::printf("%-12s edge %.4f m %7ld tets  min dihedral %5.2f deg\n", name.c_str(),
                options.edge_length, static_cast<long>(mesh.tets.rows()), quality.min_dihedral_deg);
    EXPECT_EQ(quality.inverted_count, 0) << name;
    EXPECT_GE(quality.min_dihedral_deg, kMinDihedralDeg) << name;
  }
  // A thick object keeps the job's edge; a scaled-down one has thinner walls.
  const ObjectShape ball{ObjectCategory::kSphere, {0.03}};
  EXPECT_EQ(tet_edge_for(ball, 1.0, job_edge), job_edge);
  EXPECT_EQ(tet_edge_for(ball, 0.1, job_edge), 0.5 * 0.1 * 0.06);
  // tets_across sets how many edges the thinnest part gets.
  const ObjectShape bowl = sample_shape(ObjectCategory::kBowl, 6);
  EXPECT_DOUBLE_EQ(tet_edge_for(bowl, 1.0, job_edge, 1.0), thinnest_feature(bowl));
  EXPECT_DOUBLE_EQ(tet_edge_for(bowl, 1.0, job_edge, 4.0), thinnest_feature(bowl) / 4.0);
}

}  // namespace
}  // namespace grip::objects
