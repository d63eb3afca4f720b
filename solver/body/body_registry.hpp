#pragma once
// The registry of body kinds: the one place that maps a body's description (its BodyType, and
// for an affine body its drive) to the subsystem of its kind, and that says what each type of
// description is to a reader of descriptions (its name in scene files, the parts of
// BodyDescription it takes). Nothing else in grip compares, switches or branches on BodyType:
// scripts/check-body-kinds.py keeps it so.
#include <memory>
#include <span>
#include <string_view>

#include "solver/body/body_subsystem.hpp"

namespace grip::solver {

// One type of body description, as a reader of descriptions (a scene file's) sees it.
struct BodyTypeInfo {
  BodyType type;
  std::string_view name;  // as scene files name it
  // Moved by its script (velocity, angular velocity, keyframes): it has no DOFs and may carry
  // pins.
  bool scripted = false;
  // A tet mesh of an elastic material (youngs, poisson, damping) whose vertices may be pinned.
  bool soft = false;
  // Kept near a rotation by an orthogonality energy (orthogonality_stiffness); may be driven.
  bool orthogonality = false;
};

// Every type, in the order scene files list them; and one type's row.
std::span<const BodyTypeInfo> body_types();
const BodyTypeInfo& body_type_info(BodyType type);

// The subsystems of one model, one per kind (FEM, affine, driven, kinematic).
class BodyRegistry {
 public:
  BodyRegistry();
  ~BodyRegistry();

  struct Entry {
    BodySubsystem* kind = nullptr;
    int local = 0;  // the body's index among its kind's bodies
  };
  // Puts the body described (body `body` of the scene) into its kind: validates its description
  // (std::invalid_argument naming the body) and builds its static data.
  Entry add(const BodyDescription& description, int body);

 private:
  BodySubsystem& kind_of(const BodyDescription& description);

  std::unique_ptr<BodySubsystem> kinds_[4];
};

}  // namespace grip::solver
