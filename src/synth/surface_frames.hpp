#pragma once
// Local surface frames from neighbourhood normals, as GPD computes them: the eigenvectors of
// the sum of n n^T over the sample normals within a radius give the surface normal (largest
// eigenvalue), the curvature axis (smallest: the direction the normals vary least along) and
// the binormal between them.
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "src/geometry/surface_sampling.hpp"

namespace grip::synth {

struct SurfaceFrame {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;          // unit, on the side of the sample's own normal (outward)
  Eigen::Vector3d binormal;        // unit, curvature_axis x normal
  Eigen::Vector3d curvature_axis;  // unit; (normal, binormal, curvature_axis) is right-handed
};

class SurfaceFrames {
 public:
  // `cloud` is kept by reference: it must outlive this object. `radius` > 0 (m). Builds a
  // kd-tree (CGAL) over the cloud points.
  SurfaceFrames(const geometry::SurfaceSamples& cloud, double radius);
  ~SurfaceFrames();
  SurfaceFrames(const SurfaceFrames&) = delete;
  SurfaceFrames& operator=(const SurfaceFrames&) = delete;

  // The frame at cloud point `index`. Thread-safe.
  SurfaceFrame at(int index) const;

  // Indices of the cloud points within `radius` of `point`, ascending. Thread-safe.
  std::vector<int> neighbours(const Eigen::Vector3d& point) const;

 private:
  struct Impl;
  const geometry::SurfaceSamples& cloud_;
  double radius_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grip::synth
