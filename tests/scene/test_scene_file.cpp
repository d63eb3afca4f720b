// Scene files: what they build, and one clear error for each kind of mistake.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "src/config/config.hpp"
#include "src/geometry/mesh_io.hpp"
#include "src/scene/scene_file.hpp"
#include "src/scene/scene_run.hpp"
#include "src/scene/sim_parameters.hpp"
#include "tests/config/parameter_samples.hpp"

namespace grip::scene {
namespace {

// Per process: ctest runs each test case as its own process, possibly in parallel.
std::filesystem::path write_scene(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + name);
  std::ofstream(path) << text;
  return path;
}

const std::string kGround = R"(
[[body]]
name = "ground"
type = "kinematic"
shape = "box"
size = [1, 1, 0.02]
position = [0, 0, -0.01]
)";

const std::string kDrop = "\n[sim]\ndt = 0.01\nduration = 0.2\nkappa = \"auto\"\n" + kGround + R"(
[[body]]
name = "ball"
type = "affine"
shape = "sphere"
radius = 0.02
position = [0, 0, 0.05]
rotation = [90, 0, 0]
density = 800

[[body]]
name = "jelly"
type = "fem"
shape = "box"
size = [0.02, 0.02, 0.02]
resolution = 0.01
position = [0.1, 0, 0.0115]
youngs = 2e5
damping = 0.002

[[contact]]
bodies = ["ball", "ground"]
friction = 0.9
)";

TEST(SceneFile, BuildsBodiesParametersAndContacts) {
  const SceneFile file = load_scene_file(write_scene("grip_scene_drop.toml", kDrop));
  EXPECT_DOUBLE_EQ(file.duration, 0.2);
  EXPECT_TRUE(file.scene.sim.adaptive_kappa);
  ASSERT_EQ(file.scene.bodies.size(), 3u);
  EXPECT_EQ(file.scene.bodies[0].type, solver::BodyType::kKinematic);
  EXPECT_EQ(file.scene.bodies[1].type, solver::BodyType::kAffine);
  EXPECT_EQ(file.scene.bodies[2].type, solver::BodyType::kFem);
  EXPECT_EQ(file.scene.bodies[2].tets.rows(), 6 * 2 * 2 * 2);
  EXPECT_DOUBLE_EQ(file.scene.bodies[2].material.damping, 0.002);
  EXPECT_EQ(file.scene.bodies[1].material.damping, 0.0);
  // Extrinsic XYZ degrees: 90 about x takes y to z.
  const Eigen::Vector3d y = file.scene.bodies[1].pose.rotation * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(y.z(), 1.0, 1e-12);
  ASSERT_EQ(file.scene.contacts.size(), 1u);
  EXPECT_EQ(file.scene.contacts[0].body_a, 1);
  EXPECT_DOUBLE_EQ(file.scene.contacts[0].friction, 0.9);
}

// Every row of the solver's parameter table is a [sim] key: read into its setting, and refused
// outside its range, naming the key (the job reader's [physics] is checked in tests/farm).
TEST(SceneFile, SimTakesEverySolverParameter) {
  const std::string bodies = kDrop.substr(kDrop.find("[[body]]"));
  const solver::SimParameters defaults;
  for (const auto& row : sim_parameter_table()) {
    const std::string value = config::testing::inside_value(row, defaults);
    const std::string key = std::string(row.key);
    const SceneFile file = load_scene_file(write_scene(
        "grip_scene_row.toml", "[sim]\n" + key + " = " + value + "\nduration = 0.5\n" + bodies));
    EXPECT_EQ(config::number_text(config::testing::field_value(row, file.scene.sim)),
              config::number_text(std::stod(value)))
        << key;
    try {
      load_scene_file(write_scene(
          "grip_scene_row.toml",
          "[sim]\n" + key + " = " + config::testing::outside_value(row) + "\n" + bodies));
      ADD_FAILURE() << key << " = " << config::testing::outside_value(row) << " was read";
    } catch (const config::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("key 'sim." + key + "' must"), std::string::npos)
          << e.what();
    }
  }
}

TEST(SceneFile, RunsAndReportsTheInvariants) {
  const std::string path = write_scene("grip_scene_drop.toml", kDrop);
  const BatchReport batch = run_scenes({load_scene_file(path)}, {path}, true, 1);
  ASSERT_EQ(batch.scenes.size(), 1u);
  const SceneReport& report = batch.scenes[0];
  EXPECT_EQ(report.scene, path);
  EXPECT_TRUE(report.ok) << report.failure;
  EXPECT_EQ(report.steps, 20);
  EXPECT_TRUE(report.intersection_free);
  EXPECT_GT(report.min_volume_ratio, 0.0);
  ASSERT_EQ(report.trace.size(), 20u);
  // The ball fell onto the ground and rests on it.
  EXPECT_NEAR(report.bodies[1].com.z(), 0.02, 2e-3);
  std::ostringstream json;
  write_json(json, batch, true);
  EXPECT_NE(json.str().find("\"status\": \"ok\""), std::string::npos);
  EXPECT_NE(json.str().find("\"threads\": 1"), std::string::npos);
  EXPECT_NE(json.str().find("\"trace\""), std::string::npos);
}

TEST(SceneFile, ScenesRunAsOneBatchReportInOrderAndMatchTheirSoloRuns) {
  // Two scenes of different lengths: the short one retires while the long one goes on.
  const std::string drop = write_scene("grip_scene_drop.toml", kDrop);
  std::string short_text = kDrop;
  short_text.replace(short_text.find("duration = 0.2"), 14, "duration = 0.1");
  const std::string shorter = write_scene("grip_scene_short.toml", short_text);
  const BatchReport together =
      run_scenes({load_scene_file(shorter), load_scene_file(drop)}, {shorter, drop}, false, 2);
  ASSERT_EQ(together.scenes.size(), 2u);
  EXPECT_EQ(together.scenes[0].scene, shorter);
  EXPECT_EQ(together.scenes[0].steps, 10);
  EXPECT_EQ(together.scenes[1].steps, 20);
  const BatchReport alone = run_scenes({load_scene_file(drop)}, {drop}, false, 1);
  for (std::size_t b = 0; b < alone.scenes[0].bodies.size(); ++b) {
    EXPECT_TRUE(alone.scenes[0].bodies[b].com == together.scenes[1].bodies[b].com) << b;
  }
  EXPECT_EQ(alone.scenes[0].newton_total, together.scenes[1].newton_total);
}

std::string error_of(const std::string& text) {
  try {
    load_scene_file(write_scene("grip_scene_bad.toml", text));
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

// A tet mesh file from another tool: an FEM body's tets as the file has them (here a 2 cm
// cube cut into five tets, written as Gmsh 2.2 with every tet flipped), or a rigid body's
// boundary; a mesh that cannot be simulated is refused naming the key and the file.
TEST(SceneFile, ABodyFromATetMeshFileFallsOntoTheGround) {
  geometry::TetMesh cube;
  cube.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    cube.vertices.row(i) << 0.02 * (i & 1), 0.02 * ((i >> 1) & 1), 0.02 * ((i >> 2) & 1);
  }
  cube.tets.resize(5, 4);
  cube.tets << 2, 1, 4, 7, 1, 0, 2, 4, 2, 3, 1, 7, 4, 5, 7, 1, 7, 6, 4, 2;  // all negative
  const auto folder = std::filesystem::path(write_scene("grip_scene_tets.toml", "")).parent_path();
  const std::string mesh_name = std::to_string(::getpid()) + "_cube.msh";
  geometry::write_msh(folder / mesh_name, cube);
  const std::string scene = "[sim]\ndt = 0.01\nduration = 0.1\n" + kGround + R"(
[[body]]
name = "cube"
type = "fem"
shape = "mesh"
file = ")" + mesh_name + R"("
position = [0, 0, 0.005]
youngs = 1e5
)";
  const std::string path = write_scene("grip_scene_tets.toml", scene);
  const SceneFile file = load_scene_file(path);
  ASSERT_EQ(file.scene.bodies[1].tets.rows(), 5);
  const BatchReport batch = run_scenes({file}, {path}, false, 1);
  EXPECT_TRUE(batch.scenes[0].ok) << batch.scenes[0].failure;
  EXPECT_TRUE(batch.scenes[0].intersection_free);
  EXPECT_GT(batch.scenes[0].min_volume_ratio, 0.0);

  std::string rigid = scene;
  rigid.replace(rigid.find("type = \"fem\""), 12, "type = \"affine\"");
  rigid.replace(rigid.find("youngs = 1e5"), 12, "density = 500");
  const SceneFile affine = load_scene_file(write_scene("grip_scene_tets.toml", rigid));
  EXPECT_EQ(affine.scene.bodies[1].triangles.rows(), 12);  // the cube's six faces, halved

  EXPECT_NE(error_of(scene + "resolution = 0.01\n")
                .find("key 'body[1].resolution' does not "
                      "apply to a tet mesh file"),
            std::string::npos);
  cube.tets.row(0) << 1, 2, 4, 7;  // one tet back to positive: a mix
  geometry::write_msh(folder / mesh_name, cube);
  const std::string mixed = error_of(scene);
  EXPECT_NE(mixed.find("key 'body[1].file' cannot be used"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("1 of 5 tets are inverted"), std::string::npos) << mixed;
}

TEST(SceneFile, MistakesAreOneLineErrorsNamingFileLineAndKey) {
  const std::string body = "[[body]]\nname = \"b\"\ntype = \"affine\"\nshape = \"box\"\n";
  EXPECT_NE(error_of(body + "size = [0.1, 0.1, 0.1]\ndensty = 3\n")
                .find("grip_scene_bad.toml:6: unknown key 'body[0].densty'; did you mean "
                      "'body[0].density'?"),
            std::string::npos);
  EXPECT_NE(error_of(body + "size = [0.1, 0.1, -0.1]\n")
                .find("key 'body[0].size' must hold three positive"),
            std::string::npos);
  EXPECT_NE(error_of(body + "size = [0.1, 0.1, 0.1]\nyoungs = 1e6\n")
                .find("key 'body[0].youngs' applies to FEM bodies only"),
            std::string::npos);
  EXPECT_NE(error_of(body + "size = [0.1, 0.1, 0.1]\ndamping = 0.01\n")
                .find("key 'body[0].damping' applies to FEM bodies only"),
            std::string::npos);
  const std::string fem = "[[body]]\nname = \"f\"\ntype = \"fem\"\nshape = \"box\"\n";
  EXPECT_NE(error_of(fem + "size = [0.1, 0.1, 0.1]\nresolution = 0.05\ndamping = -1\n")
                .find("grip_scene_bad.toml:7: key 'body[0].damping' must be >= 0 (s)"),
            std::string::npos);
  EXPECT_NE(error_of("[sim]\ndt = 0\n" + body + "size = [0.1, 0.1, 0.1]\n")
                .find("grip_scene_bad.toml:2: key 'sim.dt' must be positive"),
            std::string::npos);
  EXPECT_NE(error_of(body +
                     "size = [0.1, 0.1, 0.1]\n[[contact]]\nbodies = [\"b\", \"c\"]\nfriction = 1\n")
                .find("names no body: \"c\""),
            std::string::npos);
  EXPECT_NE(
      error_of("[[body]]\nname = \"m\"\ntype = \"affine\"\nshape = \"mesh\"\nfile = \"nope.obj\"\n")
          .find("key 'body[0].file' cannot be used"),
      std::string::npos);
  EXPECT_NE(error_of("[sim]\ndt = 0.01\n").find("a scene needs at least one [[body]]"),
            std::string::npos);
}

TEST(SceneFile, StepCountsAndTetCountsPastTheLimitsAreRefusedBeforeAnythingIsBuilt) {
  const std::string body =
      "[[body]]\nname = \"b\"\ntype = \"affine\"\nshape = \"box\"\n"
      "size = [0.1, 0.1, 0.1]\n";
  // 2^32 and 2^31 steps: once wrapped to 0 steps, once to a run that never ended.
  for (const char* duration : {"4294967296", "2147483648"}) {
    const std::string error =
        error_of("[sim]\ndt = 1\nduration = " + std::string(duration) + "\n" + body);
    EXPECT_NE(error.find("grip_scene_bad.toml:3: key 'sim.duration' makes"), std::string::npos)
        << error;
    EXPECT_NE(error.find("more than the 10000000 a scene may run; shorten duration or raise dt"),
              std::string::npos)
        << error;
  }
  EXPECT_NE(error_of("[sim]\ndt = 1e-300\n" + body)
                .find("grip_scene_bad.toml:2: key 'sim.dt' makes 1e+300 steps"),
            std::string::npos);
  EXPECT_NE(error_of("[sim]\ndt = 0.01\nduration = 0.004\n" + body)
                .find("key 'sim.duration' makes no step (duration 0.004 s, dt 0.01 s)"),
            std::string::npos);
  const std::string cube =
      "[[body]]\nname = \"j\"\ntype = \"fem\"\nshape = \"box\"\nsize = [0.04, 0.04, 0.04]\n";
  EXPECT_NE(error_of(cube + "resolution = 1e-5\n")
                .find("grip_scene_bad.toml:6: key 'body[0].resolution' = 1e-05 m would make "
                      "about 3.84e+11 tets, more than the 5000000 allowed"),
            std::string::npos);
  EXPECT_NE(error_of(cube + "resolution = 2e-4\n").find("about 4.8e+07 tets"), std::string::npos);
  // Shapes meshed by CGAL are estimated from their volume.
  EXPECT_NE(error_of("[[body]]\nname = \"s\"\ntype = \"fem\"\nshape = \"sphere\"\n"
                     "radius = 0.02\nresolution = 1e-4\n")
                .find("key 'body[0].resolution' = 0.0001 m would make about 2.8e+08 tets"),
            std::string::npos);
  // Within the limits nothing changes.
  const SceneFile ok = load_scene_file(write_scene(
      "grip_scene_ok.toml", "[sim]\ndt = 0.01\nduration = 0.05\n" + cube + "resolution = 0.01\n"));
  EXPECT_EQ(ok.steps(), 5);
  EXPECT_EQ(ok.scene.bodies[0].tets.rows(), 6 * 4 * 4 * 4);
}

}  // namespace
}  // namespace grip::scene
