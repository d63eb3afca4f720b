// Tests of the gripper registry: names as typed, lookups both ways, building each kind.
#include "src/grippers/gripper_registry.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace grip::grippers {
namespace {

TEST(GripperRegistry, NamesAsTypedInTableOrder) {
  EXPECT_EQ(gripper_names(), (std::vector<std::string>{"fin-ray", "parallel-jaw", "leap"}));
  EXPECT_EQ(gripper_name_list(), "fin-ray, parallel-jaw or leap");
}

TEST(GripperRegistry, EveryKindIsFoundByItsNameAndItsValue) {
  for (const GripperType& type : gripper_types()) {
    EXPECT_EQ(&gripper_type(type.name), &type);
    EXPECT_EQ(&gripper_type(type.kind), &type);
    EXPECT_EQ(find_gripper_type(type.name), &type);
    EXPECT_NE(type.make_parallel == nullptr, type.hand_files == nullptr) << type.name;
  }
  EXPECT_EQ(gripper_type("fin-ray").kind, GripperKind::kFinRay);
  EXPECT_EQ(gripper_type("parallel-jaw").kind, GripperKind::kParallelJaw);
  EXPECT_EQ(gripper_type("leap").kind, GripperKind::kLeap);
}

TEST(GripperRegistry, AnUnknownNameListsTheKnownOnes) {
  EXPECT_EQ(find_gripper_type("robotiq"), nullptr);
  EXPECT_EQ(find_gripper_type("Fin-Ray"), nullptr);
  try {
    gripper_type("robotiq");
    FAIL() << "no error for an unknown gripper";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'robotiq'"), std::string::npos) << message;
    for (const std::string& name : gripper_names()) {
      EXPECT_NE(message.find(name), std::string::npos) << message;
    }
  }
}

TEST(GripperRegistry, BuildsEachKindAsItsFamily) {
  const ParallelGripper fin_ray = make_parallel_gripper(GripperKind::kFinRay);
  EXPECT_EQ(fin_ray.name, "umi_soft");
  EXPECT_TRUE(fin_ray.soft_finger.has_value());
  const ParallelGripper jaws = make_parallel_gripper(GripperKind::kParallelJaw);
  EXPECT_EQ(jaws.name, "rigid_jaw");
  EXPECT_FALSE(jaws.soft_finger.has_value());
  EXPECT_FALSE(gripper_type(GripperKind::kFinRay).is_hand());
  EXPECT_EQ(gripper_type(GripperKind::kFinRay).joints, 1);

  ASSERT_TRUE(gripper_type(GripperKind::kLeap).is_hand());
  for (const HandSide side : {HandSide::kRight, HandSide::kLeft}) {
    const HandModel hand = make_hand(GripperKind::kLeap, side);
    EXPECT_EQ(hand.kinematics.dof_count(), gripper_type(GripperKind::kLeap).joints);
  }
  EXPECT_THROW(make_parallel_gripper(GripperKind::kLeap), std::invalid_argument);
  EXPECT_THROW(make_hand(GripperKind::kParallelJaw, HandSide::kRight), std::invalid_argument);
}

}  // namespace
}  // namespace grip::grippers
