#include "src/trial/vtk_series.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace grip::trial {

namespace {

constexpr int kVtkTriangle = 5;
constexpr int kVtkTetra = 10;

std::ofstream open_for_writing(const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot write the VTK file");
  out.precision(9);
  return out;
}

void write_frame(const std::filesystem::path& file, const solver::Model& model,
                 const BodyFrame& frame) {
  const auto& bodies = model.bodies();
  std::vector<int> connectivity, offsets, types, body_of_cell;
  std::vector<double> stress;
  int point_offset = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::span<const std::array<int, 4>> tets = bodies[b].kind->tets(bodies[b].local);
    if (!tets.empty()) {
      for (std::size_t t = 0; t < tets.size(); ++t) {
        for (int v : tets[t]) connectivity.push_back(point_offset + v);
        offsets.push_back(static_cast<int>(connectivity.size()));
        types.push_back(kVtkTetra);
        body_of_cell.push_back(static_cast<int>(b));
        stress.push_back(frame.stress[b][static_cast<Eigen::Index>(t)]);
      }
    } else {
      const solver::Triangles& triangles = model.scene().bodies[b].triangles;
      for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
        for (int c = 0; c < 3; ++c) connectivity.push_back(point_offset + triangles(t, c));
        offsets.push_back(static_cast<int>(connectivity.size()));
        types.push_back(kVtkTriangle);
        body_of_cell.push_back(static_cast<int>(b));
        stress.push_back(0.0);
      }
    }
    point_offset += static_cast<int>(frame.vertices[b].rows());
  }

  std::ofstream out = open_for_writing(file);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n<FieldData>\n"
      << "<DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">"
      << frame.time << "</DataArray>\n</FieldData>\n"
      << "<Piece NumberOfPoints=\"" << point_offset << "\" NumberOfCells=\"" << types.size()
      << "\">\n<Points>\n"
      << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const geometry::Vertices& v : frame.vertices) {
    for (Eigen::Index r = 0; r < v.rows(); ++r)
      out << v(r, 0) << ' ' << v(r, 1) << ' ' << v(r, 2) << '\n';
  }
  out << "</DataArray>\n</Points>\n<Cells>\n"
      << "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (int c : connectivity) out << c << ' ';
  out << "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (int o : offsets) out << o << ' ';
  out << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (int t : types) out << t << ' ';
  out << "\n</DataArray>\n</Cells>\n<CellData Scalars=\"von_mises\">\n"
      << "<DataArray type=\"Float64\" Name=\"von_mises\" format=\"ascii\">\n";
  for (double s : stress) out << s << ' ';
  out << "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
  for (int b : body_of_cell) out << b << ' ';
  out << "\n</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  if (!out) throw std::runtime_error(file.string() + ": writing the VTK file failed");
}

}  // namespace

void write_vtk_series(const std::filesystem::path& dir, const std::string& stem,
                      const solver::Model& model, const std::vector<BodyFrame>& frames) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error)
    throw std::runtime_error(dir.string() + ": cannot create the folder: " + error.message());
  std::ofstream pvd = open_for_writing(dir / (stem + ".pvd"));
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t f = 0; f < frames.size(); ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "_%04zu.vtu", f);
    const std::string file = stem + name;
    write_frame(dir / file, model, frames[f]);
    pvd << "<DataSet timestep=\"" << f << "\" part=\"0\" file=\"" << file << "\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  if (!pvd) throw std::runtime_error((dir / (stem + ".pvd")).string() + ": writing failed");
}

}  // namespace grip::trial
