#include "src/trial/vtk_series.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <fstream>
#include <sstream>
#include <string>

#include "src/geometry/primitives.hpp"
#include "src/scene/primitives.hpp"

namespace grip::trial {
namespace {

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(VtkSeries, WritesOneGridPerFrameAndASeriesFile) {
  // A soft block (FEM: tets with stress) and a kinematic box (triangles).
  solver::SceneDescription scene;
  solver::BodyDescription soft;
  soft.name = "soft";
  soft.type = solver::BodyType::kFem;
  scene::set_fem_mesh(soft, scene::box_tets(Eigen::Vector3d(0.02, 0.02, 0.02), 0.01));
  solver::BodyDescription plate;
  plate.name = "plate";
  plate.type = solver::BodyType::kKinematic;
  const geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d(0.05, 0.05, 0.01));
  plate.vertices = box.vertices;
  plate.triangles = box.triangles;
  plate.pose.position = Eigen::Vector3d(0, 0, -0.02);
  scene.bodies = {soft, plate};
  const auto model = solver::Model::build(scene);

  std::vector<BodyFrame> frames(3);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    frames[f].time = 0.01 * f;
    frames[f].vertices = {soft.vertices, plate.vertices};
    frames[f].stress = {Eigen::VectorXd::Constant(soft.tets.rows(), 100.0 * f), Eigen::VectorXd()};
  }
  const auto dir =
      std::filesystem::temp_directory_path() / ("grip_vtk_series_" + std::to_string(::getpid()));
  write_vtk_series(dir, "trial", *model, frames);

  const std::string pvd = read(dir / "trial.pvd");
  EXPECT_EQ(count(pvd, "<DataSet "), 3);
  EXPECT_NE(pvd.find("file=\"trial_0002.vtu\""), std::string::npos);
  const std::string vtu = read(dir / "trial_0002.vtu");
  const int cells = static_cast<int>(soft.tets.rows() + plate.triangles.rows());
  const int points = static_cast<int>(soft.vertices.rows() + plate.vertices.rows());
  EXPECT_NE(vtu.find("NumberOfPoints=\"" + std::to_string(points) + "\""), std::string::npos);
  EXPECT_NE(vtu.find("NumberOfCells=\"" + std::to_string(cells) + "\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"von_mises\""), std::string::npos);
  // Frame 2's tets carry 200 Pa, the plate's triangles 0.
  const auto stress_at = vtu.find("Name=\"von_mises\"");
  const std::string stress = vtu.substr(vtu.find('\n', stress_at) + 1);
  std::istringstream values(stress);
  for (Eigen::Index t = 0; t < soft.tets.rows(); ++t) {
    double s = 0;
    values >> s;
    ASSERT_EQ(s, 200.0);
  }
  double s = -1;
  values >> s;
  EXPECT_EQ(s, 0.0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace grip::trial
