#include "io/candidate_record.hpp"

namespace grip::io {

std::string_view to_string(Status status) {
  switch (status) {
    case Status::kPending:
      return "pending";
    case Status::kSuccess:
      return "success";
    case Status::kFailure:
      return "failure";
  }
  return "unknown";
}

std::string_view to_string(FailureKind kind) {
  switch (kind) {
    case FailureKind::kNone:
      return "none";
    case FailureKind::kInitialPenetration:
      return "initial_penetration";
    case FailureKind::kNoContact:
      return "no_contact";
    case FailureKind::kLostContact:
      return "lost_contact";
    case FailureKind::kDisplaced:
      return "displaced";
    case FailureKind::kNewtonLimit:
      return "newton_limit";
    case FailureKind::kNumerical:
      return "numerical";
    case FailureKind::kUnsettled:
      return "unsettled";
  }
  return "unknown";
}

}  // namespace grip::io
