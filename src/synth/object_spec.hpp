#pragma once
// The object a `grip synth` run grasps, from its command-line spec: a procedural category name
// (the shape drawn from the seed) or the path of a surface mesh (repaired into a closed solid).
#include <cstdint>
#include <string>

#include "src/geometry/mesh.hpp"
#include "src/objects/object_library.hpp"

namespace grip::synth {

// A mesh file's coordinates are multiplied by `scale` (meshes often come in other units).
// Throws std::invalid_argument naming the spec when it is neither a known category nor an
// existing file or when scale is not positive, and whatever reading or repairing the mesh
// throws (naming the file).
geometry::SurfaceMesh load_object(const std::string& spec, std::uint64_t seed, double scale = 1.0);

// The tet edge length to mesh the object with: for a category, objects::tet_edge_for its
// shape scaled by `category_scale` (its thinnest part over `tets_across` when that is below
// `requested`); for a mesh file, `requested`.
double object_tet_edge(const std::string& spec, std::uint64_t seed, double category_scale,
                       double requested, double tets_across = objects::kDefaultTetsAcross);

// For a mesh file, a hash of its bytes (64-bit FNV-1a, 16 hex digits), which says whether the
// file changed since candidates were synthesized on it; empty for a category.
std::string object_file_hash(const std::string& spec);

}  // namespace grip::synth
