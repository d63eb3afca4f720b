#include "src/objects/domain_randomization.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "src/objects/seeded_uniform.hpp"

namespace grip::objects {
namespace {

void check_range(const char* name, double min, double max, double lowest, bool open_low) {
  const bool low_ok = open_low ? min > lowest : min >= lowest;
  if (!(low_ok && min <= max && std::isfinite(max))) {
    throw std::invalid_argument(std::string("domain randomization: the ") + name + " range [" +
                                std::to_string(min) + ", " + std::to_string(max) + "] is invalid");
  }
}

// Separate streams keep, e.g., the friction of seed s the same when another range changes.
enum Stream : std::uint32_t { kScale = 100, kModulus, kPoisson, kDensity, kFriction };

}  // namespace

ObjectMaterial randomize_material(const RandomizationRanges& ranges, std::uint64_t seed) {
  check_range("scale", ranges.scale_min, ranges.scale_max, 0.0, true);
  check_range("Young's modulus", ranges.youngs_modulus_min, ranges.youngs_modulus_max, 0.0, true);
  check_range("Poisson ratio", ranges.poisson_ratio_min, ranges.poisson_ratio_max, 0.0, false);
  if (!(ranges.poisson_ratio_max < 0.5)) {
    throw std::invalid_argument("domain randomization: the Poisson ratio must stay below 0.5");
  }
  check_range("density", ranges.density_min, ranges.density_max, 0.0, true);
  check_range("friction", ranges.friction_min, ranges.friction_max, 0.0, false);

  ObjectMaterial material;
  material.scale = SeededUniform(seed, kScale)(ranges.scale_min, ranges.scale_max);
  material.youngs_modulus = std::exp(SeededUniform(seed, kModulus)(
      std::log(ranges.youngs_modulus_min), std::log(ranges.youngs_modulus_max)));
  material.poisson_ratio =
      SeededUniform(seed, kPoisson)(ranges.poisson_ratio_min, ranges.poisson_ratio_max);
  material.density = SeededUniform(seed, kDensity)(ranges.density_min, ranges.density_max);
  material.friction = SeededUniform(seed, kFriction)(ranges.friction_min, ranges.friction_max);
  return material;
}

geometry::SurfaceMesh scaled(const geometry::SurfaceMesh& surface, double scale) {
  geometry::SurfaceMesh result = surface;
  result.vertices *= scale;
  return result;
}

}  // namespace grip::objects
