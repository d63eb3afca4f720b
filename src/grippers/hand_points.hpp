#pragma once
// The points a dexterous grasp synthesizer needs on a hand: contact candidates (points on link
// surfaces with outward normals) and self-penetration keypoints (spheres), all in link frames.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace grip::grippers {

struct ContactCandidate {
  std::string link;
  Eigen::Vector3d position;  // m, link frame
  Eigen::Vector3d normal;    // unit, outward, link frame
};

struct PenetrationSphere {
  std::string link;
  Eigen::Vector3d center;  // m, link frame
  double radius = 0.0;     // m
};

struct HandPoints {
  std::vector<ContactCandidate> contacts;
  std::vector<PenetrationSphere> keypoints;
};

// TOML: arrays of tables [[contact]] (link, position, normal) and [[keypoint]] (link, center,
// radius). Reading throws std::runtime_error naming the file, the entry, its line and the key.
HandPoints read_hand_points(const std::filesystem::path& file);
void write_hand_points(const std::filesystem::path& file, const HandPoints& points,
                       const std::string& header_comment);

}  // namespace grip::grippers
