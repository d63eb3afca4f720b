#pragma once
// A trial's recorded frames as a ParaView-readable series: one VTK XML unstructured grid
// (.vtu, ASCII) per frame holding every body (FEM bodies as tetrahedra, others as their
// surface triangles) with von Mises stress as cell data, and a .pvd file listing them.
#include <filesystem>
#include <string>
#include <vector>

#include "solver/model/model.hpp"
#include "src/trial/trial_outcome.hpp"

namespace grip::trial {

// Writes DIR/STEM_NNNN.vtu for each frame and DIR/STEM.pvd (timestep = frame index; the
// frame's simulated time is in each grid's field data). Cell data: `von_mises` (Pa; 0 on the
// triangles of bodies that are not FEM) and `body` (the body index). Creates DIR if needed;
// throws std::runtime_error naming the file it cannot write.
void write_vtk_series(const std::filesystem::path& dir, const std::string& stem,
                      const solver::Model& model, const std::vector<BodyFrame>& frames);

}  // namespace grip::trial
