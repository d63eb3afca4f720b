#include "solver/body/body_registry.hpp"

#include <stdexcept>

#include "solver/body/affine_bodies.hpp"
#include "solver/body/driven_bodies.hpp"
#include "solver/body/fem_bodies.hpp"
#include "solver/body/kinematic_bodies.hpp"

namespace grip::solver {
namespace {

constexpr BodyTypeInfo kBodyTypes[] = {
    {BodyType::kKinematic, "kinematic", true, false, false},
    {BodyType::kAffine, "affine", false, false, true},
    {BodyType::kFem, "fem", false, true, false},
};

// Where each kind stands in BodyRegistry::kinds_.
enum KindSlot { kFemSlot, kAffineSlot, kDrivenSlot, kKinematicSlot };

}  // namespace

std::span<const BodyTypeInfo> body_types() { return kBodyTypes; }

const BodyTypeInfo& body_type_info(BodyType type) {
  for (const BodyTypeInfo& info : kBodyTypes) {
    if (info.type == type) return info;
  }
  throw std::invalid_argument("unknown body type");
}

BodyRegistry::BodyRegistry() {
  kinds_[kFemSlot] = std::make_unique<FemBodies>();
  kinds_[kAffineSlot] = std::make_unique<AffineBodies>();
  kinds_[kDrivenSlot] = std::make_unique<DrivenBodies>();
  kinds_[kKinematicSlot] = std::make_unique<KinematicBodies>();
}

BodyRegistry::~BodyRegistry() = default;

// A driven body is an affine one with a drive.
BodySubsystem& BodyRegistry::kind_of(const BodyDescription& description) {
  switch (description.type) {
    case BodyType::kFem:
      return *kinds_[kFemSlot];
    case BodyType::kAffine:
      return *kinds_[description.drive_stiffness > 0.0 ? kDrivenSlot : kAffineSlot];
    case BodyType::kKinematic:
      break;
  }
  return *kinds_[kKinematicSlot];
}

BodyRegistry::Entry BodyRegistry::add(const BodyDescription& description, int body) {
  BodySubsystem& kind = kind_of(description);
  const int local = kind.add(description, body);
  if (description.drive_stiffness != 0.0 && &kind != kinds_[kDrivenSlot].get()) {
    invalid_body(description, "drive_stiffness must be > 0, and only an affine body is driven");
  }
  return {&kind, local};
}

}  // namespace grip::solver
