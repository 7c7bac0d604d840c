// Mimic joints (URDF <mimic>, physics/joint.h JointMimic) loaded from URDF
// text through the model builder, under every registered method that takes
// joints (a method whose contract lacks joint_couplings refuses the world):
// a position-driven master whose mimic follows q = m q_master + o for
// swept multipliers and offsets, on two hinges and on two sliders; and a
// gripper whose one driven finger closes both on a box and lifts it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "service/model/model_adder.h"
#include "service/model/model_builder.h"
#include "service/model/urdf_reader.h"
#include "service/scene/model_proto.h"
#include "service/scene/snapshot.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/scenario_tolerances.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

// |q - m q_master - o| after the first step's projection has put the mimic
// on its line: the velocity row keeps it there to the order of the
// projection tolerance; 1e-4 (rad or m) is the bound asked of a mimic
// finger, and the measured errors are below 1e-9.
constexpr double kMimicTolerance = 1e-4;

// A palm (fixed or free) with two fingers on joints of `type` (revolute or
// prismatic) whose axes mirror each other; the right finger mimics the
// left with the given multiplier and offset.
std::string TwoFingerUrdf(const std::string& type, double multiplier, double offset) {
  const std::string limit = type == "prismatic" ? "<limit lower=\"-0.05\" upper=\"0.05\" effort=\"30\" velocity=\"1\"/>"
                                                : "<limit lower=\"-1.5\" upper=\"1.5\" effort=\"30\" velocity=\"5\"/>";
  auto link = [](const std::string& name, const std::string& size, double mass) {
    return "<link name=\"" + name + "\"><inertial><mass value=\"" + std::to_string(mass) +
           "\"/><inertia ixx=\"1e-3\" iyy=\"1e-3\" izz=\"1e-3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>"
           "<collision><geometry><box size=\"" + size + "\"/></geometry></collision></link>";
  };
  char mimic[160];
  std::snprintf(mimic, sizeof mimic, "<mimic joint=\"left\" multiplier=\"%.17g\" offset=\"%.17g\"/>", multiplier,
                offset);
  return "<robot name=\"gripper\">" + link("palm", "0.24 0.08 0.04", 1.0) + link("left_finger", "0.02 0.06 0.1", 0.1) +
         link("right_finger", "0.02 0.06 0.1", 0.1) + "<joint name=\"left\" type=\"" + type +
         "\"><parent link=\"palm\"/><child link=\"left_finger\"/><origin xyz=\"-0.07 0 -0.07\"/>"
         "<axis xyz=\"1 0 0\"/>" + limit + "</joint><joint name=\"right\" type=\"" + type +
         "\"><parent link=\"palm\"/><child link=\"right_finger\"/><origin xyz=\"0.07 0 -0.07\"/>"
         "<axis xyz=\"-1 0 0\"/>" + limit + mimic + "</joint></robot>";
}

// Loads the URDF text at `base`; returns the model's record.
ModelRecord LoadUrdf(World& world, const std::string& text, const Vec3& base, bool fixed_base) {
  model::ModelDescription d;
  Status st = model::ReadUrdf(text, "<inline>", model::ModelPaths{}, model::ReadLimits{}, &d);
  EXPECT_TRUE(st.ok()) << st.message();
  model::ModelOptions options;
  options.base.position = base;
  options.fixed_base = fixed_base;
  model::ModelBuild build;
  model::PreparedModel prepared;
  ModelRecord record;
  Material material;
  material.friction = 1.0;
  if (st.ok()) st = model::BuildModel(d, options, &build);
  if (st.ok()) st = model::PrepareModel(std::move(build), world, material, &prepared);
  if (st.ok()) st = model::CommitModel(std::move(prepared), &world, &record);
  EXPECT_TRUE(st.ok()) << st.message();
  return record;
}

JointId JointNamed(const ModelRecord& r, const std::string& name) {
  for (const ModelJointEntry& j : r.joints) {
    if (j.name == name) return j.joint;
  }
  ADD_FAILURE() << "no joint " << name;
  return 0;
}

double Coordinate(const World& world, JointId id) {
  const Joint& j = *world.FindJoint(id);
  return JointPosition(j, *world.Find(j.body_a), j.body_b == kWorldBody ? nullptr : world.Find(j.body_b));
}

class MimicJointTest : public ::testing::TestWithParam<MethodConfig> {
 protected:
  // a method without joints refuses them first, one with joints but
  // without couplings the mimic
  bool Refused(const testing::MethodSim& sim) {
    const MethodContract& contract = testing::ContractOf(GetParam());
    if (!contract.joints) return testing::RefusedByContract(GetParam(), sim.world, false, "joints");
    return testing::RefusedByContract(GetParam(), sim.world, contract.joint_couplings, "mimic");
  }
};

// Verifies that the mimic finger follows m q_master + o within 1e-4 while
// a position drive swings the master through a sine (amplitude 0.5 rad or
// 2 cm, 1 Hz) for 1.5 s, with the palm fixed, for m in {1, -1, 0.5} and
// offsets 0 and 0.1 rad (5 mm), on hinges and sliders; the master tracks
// its drive, so the coupling moves both.
TEST_P(MimicJointTest, MimicFollowsTheMasterForEveryMultiplierAndOffset) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const std::string type : {"revolute", "prismatic"}) {
    const bool hinge = type == "revolute";
    for (const double m : {1.0, -1.0, 0.5}) {
      for (const double o : {0.0, hinge ? 0.1 : 0.005}) {
        testing::MethodSim sim(config.method, config.params);
        const ModelRecord r = LoadUrdf(sim.world, TwoFingerUrdf(type, m, o), Vec3(0, 0, 1), true);
        if (Refused(sim)) return;
        const JointId left = JointNamed(r, "left"), right = JointNamed(r, "right");
        JointActuator drive;
        drive.kp = hinge ? 20.0 : 400.0;
        drive.kd = hinge ? 1.0 : 20.0;
        const double amplitude = hinge ? 0.5 : 0.02;
        double worst = 0.0, reach = 0.0;
        while (sim.world.time < 1.5) {
          drive.target_position = amplitude * std::sin(2.0 * kPi * sim.world.time);
          ASSERT_TRUE(sim.world.SetJointActuator(left, drive).ok());
          sim.Step();
          const double q = Coordinate(sim.world, left);
          reach = std::max(reach, std::abs(q));
          worst = std::max(worst, std::abs(Coordinate(sim.world, right) - m * q - o));
        }
        char what[96];
        std::snprintf(what, sizeof what, "%s mimic m=%g o=%g", type.c_str(), m, o);
        std::printf("%-10s %s: worst |q - m q_master - o| %.3e, master reach %.3f\n", config.label.c_str(), what,
                    worst, reach);
        checks.Expect(what, worst, 0.0, kMimicTolerance);
        checks.Expect(std::string(what) + " master moves", reach, amplitude, 0.5 * amplitude);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a gripper whose right finger mimics the left (m = 1, the
// fingers' axes mirrored) closes both fingers on a 10 cm box with one
// drive, on the left finger only, saturated at 30 N: the coupling shares
// it, 15 N a finger. The palm, on a vertical slider to the world, lifts the
// box 10 cm over 1 s and holds it 2 s: the box rises with the palm, slips
// less than 2 mm, and the fingers stay mirrored.
TEST_P(MimicJointTest, GripperWithAMimicFingerLiftsABox) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  testing::MethodSim sim(config.method, config.params);
  testing::AddGround(sim.world, 0.0, 1.0);
  const BodyId box = testing::AddBox(sim.world, Vec3(0.05, 0.05, 0.05), Vec3(0, 0, 0.05), 0.0, 1.0);
  sim.world.Find(box)->SetMass(0.5);
  const ModelRecord r = LoadUrdf(sim.world, TwoFingerUrdf("prismatic", 1.0, 0.0), Vec3(0, 0, 0.15), false);
  if (Refused(sim)) return;
  const JointId left = JointNamed(r, "left"), right = JointNamed(r, "right");
  const BodyId palm = r.links[0].body;
  JointSettings lift;
  lift.kind = JointKind::kPrismatic;
  lift.body_a = palm;
  lift.anchor = Vec3(0, 0, 0.15);
  lift.axis = -Vec3::UnitZ();  // the slide rises with the palm
  const JointId arm_joint = testing::AddJoint(sim.world, lift);
  JointActuator finger;
  finger.target_position = 0.04;  // 2 cm into the box: the drive saturates
  finger.kp = 2000.0;
  finger.kd = 20.0;
  finger.effort_limit = 30.0;
  ASSERT_TRUE(sim.world.SetJointActuator(left, finger).ok());
  JointActuator arm;
  arm.kp = 2e4;
  arm.kd = 2.0 * std::sqrt(arm.kp * 1.7);
  arm.torque = 1.7 * testing::kG;  // feed-forward: the palm, fingers and box
  const double z0 = sim.world.Find(box)->x.z();
  double relative0 = 0.0, slip = 0.0, lifted = 0.0, mirror = 0.0;
  while (sim.world.time < 3.5) {
    const double t = sim.world.time;
    arm.target_position = std::clamp(t - 0.5, 0.0, 1.0) * 0.1;  // close, lift over 1 s, hold
    ASSERT_TRUE(sim.world.SetJointActuator(arm_joint, arm).ok());
    sim.Step();
    const double relative = sim.world.Find(box)->x.z() - sim.world.Find(palm)->x.z();
    if (t < 1.5) relative0 = relative;
    slip = std::max(slip, std::abs(relative - relative0));
    lifted = sim.world.Find(box)->x.z() - z0;
    mirror = std::max(mirror, std::abs(Coordinate(sim.world, right) - Coordinate(sim.world, left)));
  }
  std::printf("%-10s mimic gripper: box lifted %.5f m, slip %.3e m, fingers at %.4f m, mirror error %.3e m, "
              "effort %.2f N\n",
              config.label.c_str(), lifted, slip, Coordinate(sim.world, left), mirror,
              sim.world.FindJoint(left)->effort);
  checks.Expect("mimic gripper lift", lifted, 0.1, 0.005);
  checks.Expect("mimic gripper slip", slip, 0.0, 0.002);
  checks.Expect("mimic gripper mirror", mirror, 0.0, kMimicTolerance);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a snapshot carries the mimic (master, multiplier, offset)
// and restores the same world bit for bit, which then steps on as the
// original does; and that a snapshot whose mimic names a missing joint is
// refused.
TEST(MimicSnapshotTest, SnapshotKeepsTheMimic) {
  testing::MethodSim sim("impulse");
  const ModelRecord r = LoadUrdf(sim.world, TwoFingerUrdf("revolute", -0.5, 0.1), Vec3(0, 0, 1), true);
  JointActuator drive;
  drive.kp = 20.0;
  drive.kd = 1.0;
  drive.target_position = 0.3;
  ASSERT_TRUE(sim.world.SetJointActuator(JointNamed(r, "left"), drive).ok());
  for (int i = 0; i < 10; ++i) sim.Step();
  proto::Snapshot snap;
  SaveSnapshot(sim.world, *sim.method, &snap);
  World restored;
  std::shared_ptr<ContactMethod> method;
  const Status st = LoadSnapshot(snap, &restored, &method);
  ASSERT_TRUE(st.ok()) << st.message();
  const Joint* right = restored.FindJoint(JointNamed(r, "right"));
  ASSERT_NE(right, nullptr);
  EXPECT_EQ(right->mimic.master, JointNamed(r, "left"));
  EXPECT_EQ(right->mimic.multiplier, -0.5);
  EXPECT_EQ(right->mimic.offset, 0.1);
  EXPECT_EQ(HashWorldState(restored), HashWorldState(sim.world));
  for (auto& j : *snap.mutable_joints()) {
    if (j.id() == JointNamed(r, "right")) j.set_mimic_master(99);
  }
  World refused;
  const Status bad = LoadSnapshot(snap, &refused, &method);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("mimics joint 99, which does not exist"), std::string::npos) << bad.message();
}

// Verifies that the resolved form of a description (the journal's and
// MODEL_CMD FORMAT_RESOLVED's, model_proto.h) keeps a mimic, so recovery,
// REWIND and --replay load the model with it.
TEST(MimicSnapshotTest, ResolvedDescriptionKeepsTheMimic) {
  model::ModelDescription d;
  ASSERT_TRUE(model::ReadUrdf(TwoFingerUrdf("prismatic", 0.5, 0.01), "<inline>", model::ModelPaths{},
                              model::ReadLimits{}, &d)
                  .ok());
  proto::ModelDescription p;
  SaveModelDescription(d, &p);
  model::ModelDescription back;
  const Status st = LoadModelDescription(p, &back);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_TRUE(back.joints[1].mimic.has_value());
  EXPECT_EQ(back.joints[1].mimic->joint, "left");
  EXPECT_EQ(back.joints[1].mimic->multiplier, 0.5);
  EXPECT_EQ(back.joints[1].mimic->offset, 0.01);
  EXPECT_FALSE(back.joints[0].mimic.has_value());
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MimicJointTest, ::testing::ValuesIn(testing::JointedWorldConfigs()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
