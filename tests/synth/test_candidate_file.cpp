// Tests of the candidate file: exact round trips and errors that name the file and line.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "src/synth/candidate_file.hpp"

namespace grip::synth {
namespace {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("grip_synth_" + std::to_string(::getpid()) + "_" + name);
}

const CandidateObject kObject{"mug", 12345678901234567890ULL, 1.0, ""};
const grippers::GripperType& kLeap = grippers::gripper_type(grippers::GripperKind::kLeap);

Candidate hand_candidate(double shift) {
  Candidate c;
  c.gripper = grippers::GripperKind::kLeap;
  for (int h = 0; h < 2; ++h) {
    HandGrasp hand;
    hand.pose.linear() = Eigen::AngleAxisd(0.3 + h + shift, Eigen::Vector3d(1, 2, 3).normalized())
                             .toRotationMatrix();
    hand.pose.translation() = Eigen::Vector3d(0.1 / 3.0, -0.2 + shift, 1e-17);
    hand.joints = Eigen::VectorXd::LinSpaced(16, -0.3, 1.7 + shift);
    hand.contacts = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Random(4, 3);
    hand.contact_normals = hand.contacts.rowwise().normalized();
    c.hands.push_back(hand);
  }
  c.energies = {{"fc", 0.1 + shift}, {"total", 1.0 / 7.0}};
  c.min_distance = 0.0015 + shift;
  return c;
}

TEST(SynthCandidateFileTest, RoundTripIsExact) {
  const std::vector<Candidate> written{hand_candidate(0.0), hand_candidate(0.25)};
  const auto file = scratch("round_trip.txt");
  write_candidates(file, kObject, kLeap, written);
  const CandidateFile back = read_candidates(file);
  EXPECT_EQ(back.object.spec, kObject.spec);
  EXPECT_EQ(back.object.seed, kObject.seed);  // a 64-bit seed, exactly
  EXPECT_EQ(back.object.scale, kObject.scale);
  EXPECT_EQ(back.object.content_hash, "");
  EXPECT_EQ(back.gripper, "leap");
  const std::vector<Candidate>& read = back.candidates;
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].gripper, written[i].gripper);
    EXPECT_EQ(read[i].energies, written[i].energies);
    EXPECT_EQ(read[i].min_distance, written[i].min_distance);
    ASSERT_EQ(read[i].hands.size(), 2u);
    for (std::size_t h = 0; h < 2; ++h) {
      EXPECT_EQ(read[i].hands[h].pose.matrix(), written[i].hands[h].pose.matrix());
      EXPECT_EQ(read[i].hands[h].joints, written[i].hands[h].joints);
      EXPECT_EQ(read[i].hands[h].contacts, written[i].hands[h].contacts);
      EXPECT_EQ(read[i].hands[h].contact_normals, written[i].hands[h].contact_normals);
    }
  }
  std::filesystem::remove(file);
}

TEST(SynthCandidateFileTest, EmptySetRoundTrips) {
  const auto file = scratch("empty.txt");
  // A mesh path with a space, and its hash, survive the round trip.
  const CandidateObject mesh{"my meshes/teapot.obj", 3, 0.01, "0123456789abcdef"};
  write_candidates(file, mesh, kLeap, {});
  const CandidateFile back = read_candidates(file);
  EXPECT_TRUE(back.candidates.empty());
  EXPECT_EQ(back.object.spec, mesh.spec);
  EXPECT_EQ(back.object.scale, mesh.scale);
  EXPECT_EQ(back.object.content_hash, mesh.content_hash);
  std::filesystem::remove(file);
}

TEST(SynthCandidateFileTest, RefusesMixedSets) {
  Candidate other = hand_candidate(0.0);
  other.hands.pop_back();
  EXPECT_THROW(write_candidates(scratch("mixed.txt"), kObject, kLeap, {hand_candidate(0.0), other}),
               std::invalid_argument);
  // Candidates of another gripper than the file's.
  EXPECT_THROW(write_candidates(scratch("mixed.txt"), kObject,
                                grippers::gripper_type(grippers::GripperKind::kFinRay),
                                {hand_candidate(0.0)}),
               std::invalid_argument);
}

// A described gripper is written by its name and the word "described", and read back as a
// described one: the trial resolves it from the description file it is given.
TEST(SynthCandidateFileTest, ADescribedGrippersCandidatesRoundTrip) {
  const grippers::GripperType described{
      grippers::GripperKind::kDescribed, "my-soft-gripper", 1, nullptr, nullptr, false, 1.0, {}};
  Candidate c;
  c.gripper = grippers::GripperKind::kDescribed;
  HandGrasp hand;
  hand.joints = Eigen::VectorXd::Constant(1, 0.05);
  hand.contacts.resize(2, 3);
  hand.contacts.setZero();
  hand.contact_normals = hand.contacts;
  c.hands.push_back(hand);
  const auto file = scratch("described.txt");
  write_candidates(file, kObject, described, {c});
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("\ngripper my-soft-gripper described\n"), std::string::npos) << text;
  const CandidateFile back = read_candidates(file);
  EXPECT_EQ(back.gripper, "my-soft-gripper");
  ASSERT_EQ(back.candidates.size(), 1u);
  EXPECT_EQ(back.candidates[0].gripper, grippers::GripperKind::kDescribed);
  EXPECT_EQ(back.candidates[0].hands[0].joints, hand.joints);
  std::filesystem::remove(file);
}

std::string read_error(const std::filesystem::path& file) {
  try {
    read_candidates(file);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SynthCandidateFileTest, ErrorsNameFileAndLine) {
  const auto file = scratch("bad.txt");
  write_candidates(file, kObject, kLeap, {hand_candidate(0.0)});
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  in.close();
  // Break the joint values of the first hand (line 10: comment, 7 header lines, candidate line).
  const std::size_t joints = text.find(" joints ", text.find("hand position"));
  std::string broken = text;
  broken.replace(joints + 8, 1, "x");
  std::ofstream(file) << broken;
  const std::string error = read_error(file);
  EXPECT_NE(error.find(file.string() + ":10:"), std::string::npos) << error;
  EXPECT_NE(error.find("joint value"), std::string::npos) << error;
  // A non-finite pose is refused on its line.
  const std::size_t position = text.find("hand position ") + 14;
  broken = text;
  broken.replace(position, text.find(' ', position) - position, "nan");
  std::ofstream(file) << broken;
  EXPECT_NE(read_error(file).find(":10: position 'nan' is not a finite number"), std::string::npos)
      << read_error(file);

  // A quaternion that is not finite or not of unit norm, a hand or a contact point far from the
  // object: refused on their line, naming the field.
  const std::size_t quaternion = text.find(" quaternion ") + 12;
  const std::size_t matrix = text.find(" matrix ", quaternion);
  for (const auto& [replacement, expected] :
       {std::pair<std::string, std::string>{"nan 0 0 0", ":10: quaternion 'nan' is not a finite"},
        {"0 0 0 0", ":10: the quaternion is not a unit quaternion"}}) {
    broken = text;
    broken.replace(quaternion, matrix - quaternion, replacement);
    std::ofstream(file) << broken;
    EXPECT_NE(read_error(file).find(expected), std::string::npos) << read_error(file);
  }
  broken = text;
  broken.replace(position, text.find(' ', position) - position, "1e300");
  std::ofstream(file) << broken;
  EXPECT_NE(read_error(file).find(":10: position lies 1e+300 m from the object's origin; a "
                                  "candidate must lie within 10 m of it"),
            std::string::npos)
      << read_error(file);
  const std::size_t contact = text.find(' ', text.find(" contacts ", position) + 10) + 1;
  broken = text;
  broken.replace(contact, text.find(' ', contact) - contact, "-11");
  std::ofstream(file) << broken;
  EXPECT_NE(read_error(file).find(":10: contact point lies 11"), std::string::npos)
      << read_error(file);

  std::ofstream(file) << "grip-candidates 2\nobject seed 1 scale 1 hash - spec box\ngripper claw\n";
  EXPECT_NE(read_error(file).find(":3: unknown gripper 'claw'"), std::string::npos)
      << read_error(file);
  std::ofstream(file) << "grip-candidates 2\nobject seed 1 scale 1 hash - spec box\n"
                         "gripper claw custom\n";
  EXPECT_NE(read_error(file).find(":3: unexpected 'custom' after the gripper's name"),
            std::string::npos)
      << read_error(file);
  // Version 1 named no object: refused, with what to do.
  std::ofstream(file) << "grip-candidates 1\ngripper leap\n";
  EXPECT_NE(read_error(file).find(":1: unsupported format version"), std::string::npos)
      << read_error(file);
  EXPECT_NE(read_error(file).find("synthesize them again"), std::string::npos);
  EXPECT_NE(read_error(scratch("missing.txt")).find("cannot open"), std::string::npos);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace grip::synth
