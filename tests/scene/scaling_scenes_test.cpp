// Smoke tests of the scaling scenes of `make bench` (config/scenes, written
// by bench/scripts/scaling_scenes.py; BENCHMARKS.md, "Scaling"): each loads
// with the bodies and joints its header states, and steps a few steps
// under lcp without a contact between touching neighbours going deep
// or a joint coming apart. The benchmark runs them; this only keeps the
// files loadable and steppable.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "service/contact/contact_method.h"
#include "service/scene/scene_spec.h"

namespace contactsim {
namespace {

struct Scaling {
  const char* scene;
  int bodies;  // with the ground
  int fixed;   // static bodies: the ground and a joint grid's anchors
  int joints;
};

// Counts from the scenes' headers: a pyramid of base b holds b (b + 1) / 2
// boxes; the comb of an n x n grid hung from 7 anchors n (n - 1) + (n - 1) - 6
// joints.
constexpr Scaling kScenes[] = {
    {"pyramid_45.pbtxt", 1036, 1, 0},          {"pyramid_90.pbtxt", 4096, 1, 0},
    {"many_pyramids_10k.pbtxt", 10011, 1, 0},  {"joint_grid_32.pbtxt", 1025, 8, 1017},
    {"joint_grid_100.pbtxt", 10001, 8, 9993},
};

// Steps each scene takes: enough for the contacts and joints to act, few
// enough that 10,000 bodies take seconds.
constexpr int kSteps = 2;

// m: resting 1 m cubes may sink by the slop (1 mm) plus what gravity closes
// in a step; a joint's anchors stay together to the projection's tolerance
constexpr double kMaxDepth = 5e-3;
constexpr double kMaxJointGap = 1e-6;

class ScalingScenesTest : public ::testing::TestWithParam<Scaling> {};

// Verifies that the scene loads with its stated bodies, anchors and joints
// and steps kSteps steps under lcp (pgs) with shallow contacts and joints
// that hold.
TEST_P(ScalingScenesTest, LoadsAndSteps) {
  const Scaling& s = GetParam();
  SceneSpec spec;
  World world;
  ASSERT_TRUE(LoadSceneFile(std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + s.scene, &spec).ok());
  ASSERT_TRUE(BuildWorld(spec, &world).ok());
  EXPECT_EQ(static_cast<int>(world.bodies().size()), s.bodies);
  EXPECT_EQ(static_cast<int>(world.joints().size()), s.joints);
  int fixed = 0;
  for (const RigidBody& b : world.bodies()) fixed += !b.IsDynamic();
  EXPECT_EQ(fixed, s.fixed);
  std::unique_ptr<ContactMethod> method;
  ASSERT_TRUE(CreateContactMethod("lcp", &method).ok());
  CollisionDetector detector;
  ASSERT_TRUE(detector.SetThreads(2).ok());
  ContactSet contacts;
  for (int i = 0; i < kSteps; ++i) method->Step(world, detector, &contacts);
  EXPECT_TRUE(std::isfinite(KineticEnergy(world)));
  double deepest = 0.0;
  for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
  EXPECT_LT(deepest, kMaxDepth) << s.scene;
  double gap = 0.0;
  for (const Joint& j : world.joints()) {
    const RigidBody& a = *world.Find(j.body_a);
    const RigidBody& b = *world.Find(j.body_b);
    gap = std::max(gap, (a.x + a.Rotation() * j.anchor_a - b.x - b.Rotation() * j.anchor_b).norm());
  }
  EXPECT_LT(gap, kMaxJointGap) << s.scene;
}

INSTANTIATE_TEST_SUITE_P(Scenes, ScalingScenesTest, ::testing::ValuesIn(kScenes),
                         [](const ::testing::TestParamInfo<Scaling>& info) {
                           std::string name = info.param.scene;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace contactsim
