// What ranks send each other arrives bit for bit.
#include <gtest/gtest.h>

#include "farm/wire.hpp"

namespace grip::farm {
namespace {

TEST(Wire, ObjectRecordRoundTrips) {
  io::ObjectRecord r;
  r.name = "mug-3";
  r.category = "mug";
  r.scale = 1.0 / 3.0;
  r.soft = true;
  r.material = {1.234e6, 0.41, 987.6, 0.7};
  r.vertices = {0.1, -0.2, 1e-300, 4, 5, 6};
  r.triangles = {0, 1, 1};
  r.tets = {0, 1, 1, 0};
  const io::ObjectRecord back = unpack_object(pack(r));
  EXPECT_EQ(back.name, r.name);
  EXPECT_EQ(back.category, r.category);
  EXPECT_EQ(back.scale, r.scale);
  EXPECT_EQ(back.soft, r.soft);
  EXPECT_EQ(back.material.young_modulus, r.material.young_modulus);
  EXPECT_EQ(back.material.friction, r.material.friction);
  EXPECT_EQ(back.vertices, r.vertices);
  EXPECT_EQ(back.triangles, r.triangles);
  EXPECT_EQ(back.tets, r.tets);
  // A rigid object has no tets: an empty vector, whose data() is null (memcpy from and to null
  // is undefined behaviour even for no bytes, which the sanitized suite reports).
  r.soft = false;
  r.tets.clear();
  const io::ObjectRecord rigid = unpack_object(pack(r));
  EXPECT_TRUE(rigid.tets.empty());
  EXPECT_EQ(rigid.vertices, r.vertices);
}

TEST(Wire, CandidatesRoundTrip) {
  synth::Candidate c;
  c.gripper = grippers::GripperKind::kLeap;
  synth::HandGrasp hand;
  hand.pose = Eigen::Translation3d(0.1, 0.2, 1.0 / 7.0) *
              Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  hand.joints = Eigen::VectorXd::LinSpaced(16, -0.5, 1.5);
  hand.contacts.resize(2, 3);
  hand.contacts << 1, 2, 3, 4, 5, 6;
  hand.contact_normals.resize(2, 3);
  hand.contact_normals << 0, 0, 1, 0, 1, 0;
  c.hands = {hand, hand};
  c.energies = {{"fc", 0.25}, {"total", 3.5}};
  c.min_distance = 1.5e-3;
  const std::vector<synth::Candidate> back = unpack_candidates(pack({c, c}));
  ASSERT_EQ(back.size(), 2u);
  const synth::Candidate& b = back[1];
  EXPECT_EQ(b.gripper, c.gripper);
  ASSERT_EQ(b.hands.size(), 2u);
  EXPECT_EQ(b.hands[1].pose.matrix(), hand.pose.matrix());
  EXPECT_EQ(b.hands[1].joints, hand.joints);
  EXPECT_EQ(b.hands[1].contacts, hand.contacts);
  EXPECT_EQ(b.hands[1].contact_normals, hand.contact_normals);
  EXPECT_EQ(b.energies, c.energies);
  EXPECT_EQ(b.min_distance, c.min_distance);
}

TEST(Wire, TruncatedMessagesAreRefused) {
  std::string bytes = pack(std::vector<synth::Candidate>(1));
  bytes.pop_back();
  EXPECT_THROW(unpack_candidates(bytes), std::runtime_error);
}

}  // namespace
}  // namespace grip::farm
