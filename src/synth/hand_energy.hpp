#pragma once
// The grasp energy of the dexterous optimizer (DexGraspNet with the GRIP paper's normal term):
//   E = E_fc + w_dis E_dis + w_pen E_pen + w_spen E_spen + w_joints E_joints + w_normal E_normal
// and its exact gradient with respect to the hand's base translation, base rotation and joints.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"
#include "src/synth/prepared_hand.hpp"
#include "src/synth/prepared_object.hpp"

namespace grip::synth {

struct HandEnergyWeights {
  double fc = 1.0;
  double dis = 100.0;
  double pen = 100.0;
  double spen = 10.0;
  double joints = 1.0;
  double normal = 1.0;  // the paper's w
};

struct HandEnergyTerms {
  double fc = 0.0;      // || G c ||: net wrench of unit normal forces at the contacts
  double dis = 0.0;     // sum of contact-point distances to the object (m)
  double pen = 0.0;     // sum of object-point depths inside hand links (m)
  double spen = 0.0;    // sum of keypoint-sphere overlaps between non-adjacent links (m)
  double joints = 0.0;  // sum of joint-limit violations (rad)
  double normal = 0.0;  // sum_i ((R_i n_i^h) . n_i^o + 1)^2
  double total = 0.0;   // weighted sum
};

// A hand configuration: the base pose (world from palm), joint values, and the indices of the
// contact candidates (PreparedHand::contacts) taking part in E_fc, E_dis and E_normal.
struct HandState {
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  Eigen::VectorXd joints;
  std::vector<int> contacts;
};

// Gradient layout (6 + J): d/dt (base translation), d/dw (base rotation exp([w]) R about the
// base origin, world axes), d/dq (joints). The normals n_i^o are those of the object's closest
// triangles, constant almost everywhere, so they carry no derivative.
class HandEnergy {
 public:
  // `object_points`: samples of the object surface for E_pen (rows, world frame). The hand,
  // object and points are kept by reference.
  HandEnergy(const PreparedHand& hand, const PreparedObject& object,
             const geometry::Vertices& object_points, HandEnergyWeights weights = {});

  // Energy at `state` (joints within the limits); fills `gradient` when non-null.
  HandEnergyTerms evaluate(const HandState& state, Eigen::VectorXd* gradient) const;

  // Applies a step in the gradient's layout: t += d_t, R = exp([d_w]) R, q += d_q.
  static HandState moved(const HandState& state, const Eigen::VectorXd& step);

  const HandEnergyWeights& weights() const { return weights_; }

 private:
  const PreparedHand& hand_;
  const PreparedObject& object_;
  const geometry::Vertices& object_points_;
  HandEnergyWeights weights_;
};

// E_joints alone for any q (the optimizer keeps q within the limits, where it is 0), with its
// gradient: sum of max(0, q - upper) + max(0, lower - q).
double joint_limit_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& lower,
                          const Eigen::VectorXd& upper, Eigen::VectorXd* gradient);

// The approximate force-closure metric of a set of contacts with unit object normals:
// || [sum n_i ; sum x_i x n_i] ||, 0 for a balanced set; x_i relative to the torque reference
// point (the object's centroid in HandEnergy).
double force_closure_error(
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& points,
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& normals);

}  // namespace grip::synth
