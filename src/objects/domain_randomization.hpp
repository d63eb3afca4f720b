#pragma once
// Seeded domain randomization of an object's scale and material, as the GRIP paper does for
// Young's modulus, friction and scale (it gives no ranges; ours are in docs/assets.md).
#include <cstdint>

#include "src/geometry/mesh.hpp"

namespace grip::objects {

struct RandomizationRanges {
  double scale_min = 0.8;  // uniform factor on every length
  double scale_max = 1.2;
  double youngs_modulus_min = 1e5;  // Pa, log-uniform: soft foam to stiff rubber
  double youngs_modulus_max = 1e7;
  double poisson_ratio_min = 0.30;  // uniform
  double poisson_ratio_max = 0.48;
  double density_min = 500.0;  // kg/m^3, uniform: foam-filled plastic to rubber
  double density_max = 1500.0;
  double friction_min = 0.3;  // Coulomb coefficient, uniform
  double friction_max = 1.0;
};

struct ObjectMaterial {
  double scale = 1.0;
  double youngs_modulus = 1e6;  // Pa
  double poisson_ratio = 0.4;
  double density = 1000.0;  // kg/m^3
  double friction = 0.5;
};

// Draws every property from its range. Same ranges and seed, same material. Throws
// std::invalid_argument if a range is empty, inverted or physically invalid (Poisson ratio
// outside [0, 0.5), non-positive modulus, density, scale, negative friction).
ObjectMaterial randomize_material(const RandomizationRanges& ranges, std::uint64_t seed);

// The surface scaled about the origin (objects stand on z = 0, so they keep standing there).
geometry::SurfaceMesh scaled(const geometry::SurfaceMesh& surface, double scale);

}  // namespace grip::objects
