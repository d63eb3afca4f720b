#pragma once
// Quality figures of a tet mesh: dihedral angles, signed volumes, inverted and sliver counts.
#include "src/geometry/mesh.hpp"

namespace grip::geometry {

struct TetQuality {
  double min_dihedral_deg = 0.0;  // smallest dihedral angle over all tets
  double max_dihedral_deg = 0.0;  // largest dihedral angle over all tets
  double min_volume = 0.0;        // smallest signed tet volume (m^3); <= 0 means inverted
  double total_volume = 0.0;      // sum of signed tet volumes (m^3)
  int inverted_count = 0;         // tets with signed volume <= 0
  int sliver_count = 0;           // tets with a dihedral angle below the sliver bound
};

// A tet counts as a sliver when one of its six dihedral angles is below `sliver_bound_deg`.
TetQuality tet_quality(const TetMesh& mesh, double sliver_bound_deg = 5.0);

}  // namespace grip::geometry
