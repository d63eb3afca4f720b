#include "src/grippers/hand_model.hpp"

#include <stdexcept>

namespace grip::grippers {

HandModel load_hand_model(const std::filesystem::path& urdf, const std::filesystem::path& points) {
  HandModel hand{KinematicTree::from_urdf(urdf), read_hand_points(points)};
  auto check = [&](const std::string& link) {
    try {
      hand.kinematics.link_index(link);
    } catch (const std::out_of_range&) {
      throw std::runtime_error("hand points '" + points.string() + "' name link '" + link +
                               "', which URDF '" + urdf.string() + "' does not have");
    }
  };
  for (const ContactCandidate& c : hand.points.contacts) check(c.link);
  for (const PenetrationSphere& s : hand.points.keypoints) check(s.link);
  return hand;
}

}  // namespace grip::grippers
