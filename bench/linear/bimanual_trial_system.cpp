#include "bench/linear/bimanual_trial_system.hpp"

#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver/linear/sparse_cholesky.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/scene/primitives.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"

namespace grip::bench {

namespace {

const Eigen::Vector3d kBar(0.40, 0.05, 0.04);  // m: length (x), width (y, the jaws'), height

// Thrown by the recorder once it holds a contact system: ends the trial from inside its solve.
struct Captured {};

// Solves by CHOLMOD, as the environment would, until a system has more nonzeros than the
// first one (the contact-free pattern: the grippers are placed 1.5 d_hat away), keeps it and
// stops the trial.
class ContactSystemRecorder final : public solver::LinearSystemSolver {
 public:
  bool factorize(const Eigen::SparseMatrix<double>& lower) override {
    ++systems_;
    if (first_nonzeros_ < 0) first_nonzeros_ = lower.nonZeros();
    pending_ = lower.nonZeros() > first_nonzeros_;
    if (pending_) captured_.lower = lower;
    return cholesky_.factorize(lower);
  }
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    if (pending_) {
      captured_.rhs = rhs;
      captured_.newton_iterations = systems_;
      throw Captured{};
    }
    x = cholesky_.solve(rhs);
    return true;
  }
  std::string failure() const override { return "the matrix is not positive definite"; }
  bool refuses_indefinite() const override { return true; }
  const NewtonSystem& captured() const { return captured_; }

 private:
  solver::SparseCholesky cholesky_;
  long first_nonzeros_ = -1;
  bool pending_ = false;
  int systems_ = 0;
  NewtonSystem captured_;
};

}  // namespace

NewtonSystem capture_bimanual_trial_system(double cell) {
  trial::TrialObject bar;
  bar.name = "soft bar";
  bar.surface = geometry::make_box(kBar);
  bar.tets = scene::box_tets(kBar, cell);
  bar.material.density = 1000.0;
  bar.material.youngs = 1e6;  // the middle (log) of the farm's default range, 0.1-10 MPa
  bar.material.poisson = 0.4;
  const trial::TrialParameters parameters;
  // The 80 mm fin-ray fingers: the grasps below are placed for their length.
  const trial::ParallelTrialScene scene(
      bar, grippers::make_umi_soft_gripper(grippers::fin_ray_80mm_options()), parameters, 2);
  // Both grippers approach from below (-z) and close across the bar's width, 12 cm either side
  // of its middle, their jaws open 4.6 mm beyond it.
  std::vector<trial::ParallelGrasp> grasps(2);
  for (int g = 0; g < 2; ++g) {
    grasps[g].pose.translation() = Eigen::Vector3d(g == 0 ? -0.12 : 0.12, 0.0, -0.05);
    grasps[g].opening = kBar.y() + 0.0046;
  }
  auto recorder = std::make_shared<ContactSystemRecorder>();
  trial::TrialRunOptions options;
  options.threads = 1;
  options.trajectory = false;
  options.big_system_solver = recorder;
  try {
    const trial::TrialOutcome outcome =
        trial::run_trials(scene, {trial::parallel_candidate(grasps)}, options).front();
    throw std::runtime_error("the bimanual trial ended (" + outcome.failure_reason +
                             ") before its fingers touched the bar");
  } catch (const Captured&) {
    return recorder->captured();
  }
}

}  // namespace grip::bench
