// grip's side of the ipc-toolkit oracle (test_ipctk_oracle.py): for each kernel named below it
// reads DIR/<kernel>.in, rows of float64 inputs, and writes DIR/<kernel>.out, rows of grip's
// values. The row layouts are the `Kernel` table's and the Python script's; matrices are written
// row-major, distance types as their enum index (the order of ipctk's enums).
//   kernel_values DIR
#include <Eigen/Core>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "solver/kernels/accd.hpp"
#include "solver/kernels/barrier.hpp"
#include "solver/kernels/closest_point.hpp"
#include "solver/kernels/contact_barrier.hpp"
#include "solver/kernels/distance.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/friction_mollifier.hpp"
#include "solver/kernels/friction_potential.hpp"
#include "solver/kernels/relative_velocity.hpp"
#include "solver/kernels/tangent_basis.hpp"

namespace {

namespace k = grip::solver::kernels;
using Eigen::Vector3d;

// Appends a vector or matrix, row-major.
class Row {
 public:
  explicit Row(double* out) : out_(out) {}
  Row& operator<<(double v) {
    *out_++ = v;
    return *this;
  }
  template <typename Derived>
  Row& operator<<(const Eigen::MatrixBase<Derived>& m) {
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index j = 0; j < m.cols(); ++j) *out_++ = m(i, j);
    return *this;
  }

 private:
  double* out_;
};

Vector3d point(const double* in, int i) {
  return Vector3d(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
}

template <int N>
Eigen::Matrix<double, 3 * N, 1> stacked(const double* in) {
  return Eigen::Map<const Eigen::Matrix<double, 3 * N, 1>>(in);
}

struct Kernel {
  const char* name;
  int in_width;
  int out_width;
  std::function<void(const double* in, Row out)> evaluate;
};

// Friction of one contact with N vertices from its lagged positions x (3N), the displacement
// dx (3N), mu lambda and eps: tangent basis (3x2), closest-point coordinates (2, unused ones 0),
// then D, grad D and hess D in dx.
template <int N>
void friction(const double* in, Row out, const Eigen::Matrix<double, 3, 2>& basis,
              const Eigen::Vector2d& coords, const Eigen::Matrix<double, 3, 3 * N>& gamma) {
  const Eigen::Matrix<double, 3 * N, 1> dx = stacked<N>(in + 3 * N);
  const double mu_lambda = in[6 * N], eps = in[6 * N + 1];
  const Eigen::Matrix<double, 3 * N, 2> op = k::tangent_operator<N>(gamma, basis);
  out << basis << coords << k::friction_potential<N>(dx, op, mu_lambda, eps)
      << k::friction_potential_gradient<N>(dx, op, mu_lambda, eps)
      << k::friction_potential_hessian<N>(dx, op, mu_lambda, eps);
}

// In: 4 positions, d_hat, kappa, the mollifier threshold. Out: value, gradient, Hessian.
void contact_barrier(bool edge_edge, const double* in, Row out) {
  const Vector3d x[4] = {point(in, 0), point(in, 1), point(in, 2), point(in, 3)};
  const k::ContactBarrier b = k::contact_barrier(edge_edge, in[14], x, in[12], in[13], true);
  out << b.value << b.gradient << b.hessian;
}

// In: 4 positions at t = 0, 4 at t = 1, min separation, t_max. Out: toi, impact, iterations.
void accd(bool edge_edge, const double* in, Row out) {
  k::AccdOptions options;
  options.min_separation = in[24];
  options.t_max = in[25];
  const auto ccd = edge_edge ? k::edge_edge_accd : k::point_triangle_accd;
  const k::AccdResult r = ccd(point(in, 0), point(in, 1), point(in, 2), point(in, 3), point(in, 4),
                              point(in, 5), point(in, 6), point(in, 7), options);
  out << r.toi << (r.impact ? 1.0 : 0.0) << static_cast<double>(r.iterations);
}

const std::vector<Kernel>& kernels() {
  static const std::vector<Kernel> table = {
      {"point_point_distance", 6, 43,
       [](const double* in, Row out) {
         const Vector3d p0 = point(in, 0), p1 = point(in, 1);
         out << k::point_point_distance_sq(p0, p1) << k::point_point_distance_sq_gradient(p0, p1)
             << k::point_point_distance_sq_hessian(p0, p1);
       }},
      {"point_edge_distance", 9, 92,
       [](const double* in, Row out) {
         const Vector3d p = point(in, 0), e0 = point(in, 1), e1 = point(in, 2);
         const k::PointEdgeDistanceType type = k::point_edge_distance_type(p, e0, e1);
         out << static_cast<double>(type) << k::point_edge_distance_sq(p, e0, e1, type)
             << k::point_edge_distance_sq_gradient(p, e0, e1, type)
             << k::point_edge_distance_sq_hessian(p, e0, e1, type);
       }},
      {"point_triangle_distance", 12, 158,
       [](const double* in, Row out) {
         const Vector3d p = point(in, 0), t0 = point(in, 1), t1 = point(in, 2), t2 = point(in, 3);
         const k::PointTriangleDistanceType type = k::point_triangle_distance_type(p, t0, t1, t2);
         out << static_cast<double>(type) << k::point_triangle_distance_sq(p, t0, t1, t2, type)
             << k::point_triangle_distance_sq_gradient(p, t0, t1, t2, type)
             << k::point_triangle_distance_sq_hessian(p, t0, t1, t2, type);
       }},
      {"edge_edge_distance", 12, 158,
       [](const double* in, Row out) {
         const Vector3d a0 = point(in, 0), a1 = point(in, 1), b0 = point(in, 2), b1 = point(in, 3);
         const k::EdgeEdgeDistanceType type = k::edge_edge_distance_type(a0, a1, b0, b1);
         out << static_cast<double>(type) << k::edge_edge_distance_sq(a0, a1, b0, b1, type)
             << k::edge_edge_distance_sq_gradient(a0, a1, b0, b1, type)
             << k::edge_edge_distance_sq_hessian(a0, a1, b0, b1, type);
       }},
      // In: d, d_hat (any one parameterization: the function is the same).
      {"barrier", 2, 3,
       [](const double* in, Row out) {
         out << k::barrier(in[0], in[1]) << k::barrier_first_derivative(in[0], in[1])
             << k::barrier_second_derivative(in[0], in[1]);
       }},
      // In: squared distance, squared d_hat, kappa.
      {"barrier_force_magnitude", 3, 1,
       [](const double* in, Row out) { out << k::barrier_force_magnitude(in[0], in[1], in[2]); }},
      // In: x = ||a x b||^2, eps_x. Out: m, m', m''.
      {"edge_edge_mollifier_scalar", 2, 3,
       [](const double* in, Row out) {
         out << k::edge_edge_mollifier(in[0], in[1])
             << k::edge_edge_mollifier_derivative(in[0], in[1])
             << k::edge_edge_mollifier_second_derivative(in[0], in[1]);
       }},
      // In: 4 positions, 4 rest positions. Out: eps_x, x, m, grad m, hess m.
      {"edge_edge_mollifier", 24, 159,
       [](const double* in, Row out) {
         const Vector3d a0 = point(in, 0), a1 = point(in, 1), b0 = point(in, 2), b1 = point(in, 3);
         const double eps_x = k::edge_edge_mollifier_threshold(point(in, 4), point(in, 5),
                                                               point(in, 6), point(in, 7));
         out << eps_x << k::edge_edge_cross_norm_sq(a0, a1, b0, b1)
             << k::edge_edge_mollifier(a0, a1, b0, b1, eps_x)
             << k::edge_edge_mollifier_gradient(a0, a1, b0, b1, eps_x)
             << k::edge_edge_mollifier_hessian(a0, a1, b0, b1, eps_x);
       }},
      // In: y, eps. Out: f0, f1, f1 / y, d(f1 / y) / dy.
      {"friction_mollifier", 2, 4,
       [](const double* in, Row out) {
         out << k::friction_f0(in[0], in[1]) << k::friction_f1(in[0], in[1])
             << k::friction_f1_over_y(in[0], in[1])
             << k::friction_f1_over_y_derivative(in[0], in[1]);
       }},
      {"friction_point_point", 14, 6 + 2 + 1 + 6 + 36,
       [](const double* in, Row out) {
         friction<2>(in, out, k::point_point_tangent_basis(point(in, 0), point(in, 1)),
                     Eigen::Vector2d::Zero(), k::point_point_relative_velocity_jacobian());
       }},
      {"friction_point_edge", 20, 6 + 2 + 1 + 9 + 81,
       [](const double* in, Row out) {
         const Vector3d p = point(in, 0), e0 = point(in, 1), e1 = point(in, 2);
         const double alpha = k::point_edge_closest_point(p, e0, e1);
         friction<3>(in, out, k::point_edge_tangent_basis(p, e0, e1), Eigen::Vector2d(alpha, 0.0),
                     k::point_edge_relative_velocity_jacobian(alpha));
       }},
      {"friction_point_triangle", 26, 6 + 2 + 1 + 12 + 144,
       [](const double* in, Row out) {
         const Vector3d p = point(in, 0), t0 = point(in, 1), t1 = point(in, 2), t2 = point(in, 3);
         const Eigen::Vector2d beta = k::point_triangle_closest_point(p, t0, t1, t2);
         friction<4>(in, out, k::point_triangle_tangent_basis(p, t0, t1, t2), beta,
                     k::point_triangle_relative_velocity_jacobian(beta));
       }},
      {"friction_edge_edge", 26, 6 + 2 + 1 + 12 + 144,
       [](const double* in, Row out) {
         const Vector3d a0 = point(in, 0), a1 = point(in, 1), b0 = point(in, 2), b1 = point(in, 3);
         const Eigen::Vector2d coords = k::edge_edge_closest_point(a0, a1, b0, b1);
         friction<4>(in, out, k::edge_edge_tangent_basis(a0, a1, b0, b1), coords,
                     k::edge_edge_relative_velocity_jacobian(coords));
       }},
      {"contact_barrier_point_triangle", 15, 157,
       [](const double* in, Row out) { contact_barrier(false, in, out); }},
      {"contact_barrier_edge_edge", 15, 157,
       [](const double* in, Row out) { contact_barrier(true, in, out); }},
      {"accd_point_triangle", 26, 3, [](const double* in, Row out) { accd(false, in, out); }},
      {"accd_edge_edge", 26, 3, [](const double* in, Row out) { accd(true, in, out); }},
  };
  return table;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: kernel_values DIR (reads DIR/<kernel>.in, writes .out)\n");
    return 2;
  }
  const std::string dir = argv[1];
  for (const Kernel& kernel : kernels()) {
    std::ifstream in(dir + "/" + kernel.name + ".in", std::ios::binary);
    if (!in) continue;  // the script asks only for the kernels it compares
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    const std::size_t row_bytes = sizeof(double) * kernel.in_width;
    if (bytes.size() % row_bytes != 0) {
      std::fprintf(stderr, "%s.in: %zu bytes, not rows of %d doubles\n", kernel.name, bytes.size(),
                   kernel.in_width);
      return 1;
    }
    const std::size_t rows = bytes.size() / row_bytes;
    std::vector<double> inputs(rows * kernel.in_width);
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(inputs.data()));
    std::vector<double> outputs(rows * kernel.out_width);
    for (std::size_t r = 0; r < rows; ++r)
      kernel.evaluate(inputs.data() + r * kernel.in_width,
                      Row(outputs.data() + r * kernel.out_width));
    std::ofstream out(dir + "/" + kernel.name + ".out", std::ios::binary);
    out.write(reinterpret_cast<const char*>(outputs.data()),
              static_cast<std::streamsize>(sizeof(double) * outputs.size()));
    if (!out) {
      std::fprintf(stderr, "%s.out: cannot write\n", kernel.name);
      return 1;
    }
  }
  return 0;
}
