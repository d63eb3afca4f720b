#include "bench/peer/mujoco_model.hpp"

#if GRIP_HAVE_MUJOCO
#include <memory>

namespace grip::bench {
namespace {

void ignore_warning(const char*) {}

}  // namespace

void write_mesh_asset(std::ostream& x, const std::string& name, const geometry::SurfaceMesh& mesh) {
  x << "<mesh name=\"" << name << "\" vertex=\"";
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    x << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << ' ';
  }
  x << "\" face=\"";
  for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
    x << mesh.triangles(f, 0) << ' ' << mesh.triangles(f, 1) << ' ' << mesh.triangles(f, 2) << ' ';
  }
  x << "\"/>";
}

mjModel* load_model(const std::string& xml, std::string& message) {
  static const bool quiet = [] {
    mju_user_warning = ignore_warning;  // instabilities are read from mjData::warning
    return true;
  }();
  (void)quiet;
  const auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  mj_addBufferVFS(vfs.get(), "peer.xml", xml.data(), static_cast<int>(xml.size()));
  char error[1000] = "";
  mjModel* model = mj_loadXML("peer.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) message = error;
  return model;
}

Eigen::Isometry3d body_pose(const mjData* d, int body) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->xmat + 9 * body);
  pose.translation() = Eigen::Map<const Eigen::Vector3d>(d->xpos + 3 * body);
  return pose;
}

}  // namespace grip::bench
#endif
