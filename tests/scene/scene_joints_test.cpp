// Tests of joints in scene files: bodies named by a unique name, anchors in
// world coordinates, errors naming the file, the line and the field, and a
// bad joint leaving the world untouched.
#include <gtest/gtest.h>

#include "service/scene/scene_spec.h"

namespace contactsim {
namespace {

constexpr char kPendulums[] = R"pb(
bodies { name: "bob" sphere { radius: 0.05 } position { x: 0.5 z: 1 } }
bodies { name: "door" box { half_extents { x: 0.4 y: 0.02 z: 0.8 } } position { x: 2.4 z: 1 } }
joints { kind: "distance" body_a: "bob" anchor { z: 2 } }
joints {
  kind: "hinge"
  body_a: "door"
  anchor { x: 2 z: 1 }
  axis { z: 1 }
  limits { lower: -1.5 upper: 0 }
}
)pb";

// Verifies that the joints of a scene are added after its bodies, with the
// default length from the initial poses and the limits and axis as given.
TEST(SceneJoints, JointsAreBuiltFromNamesAndWorldAnchors) {
  SceneSpec scene;
  ASSERT_TRUE(ParseSceneText(kPendulums, "p.pbtxt", &scene).ok());
  World world;
  const Status st = BuildWorld(scene, &world);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(world.joints().size(), 2u);
  const Joint& rod = world.joints()[0];
  EXPECT_EQ(rod.kind, JointKind::kDistance);
  EXPECT_EQ(rod.body_a, 1);
  EXPECT_EQ(rod.body_b, kWorldBody);
  EXPECT_DOUBLE_EQ(rod.length, std::sqrt(0.5 * 0.5 + 1.0));
  const Joint& hinge = world.joints()[1];
  EXPECT_EQ(hinge.kind, JointKind::kHinge);
  EXPECT_EQ(hinge.body_a, 2);
  EXPECT_TRUE(hinge.limited);
  EXPECT_DOUBLE_EQ(hinge.lower, -1.5);
  EXPECT_TRUE(hinge.axis_a.isApprox(Vec3::UnitZ()));
  EXPECT_TRUE(hinge.anchor_a.isApprox(Vec3(-0.4, 0, 0)));
}

// Verifies that a prismatic joint of a scene file takes its axis, limits
// (m), damping and friction.
TEST(SceneJoints, PrismaticJointsTakeLimitsDampingAndFriction) {
  constexpr char kSlider[] = R"pb(
bodies { name: "carriage" box { half_extents { x: 0.1 y: 0.1 z: 0.1 } } position { z: 1 } }
joints {
  kind: "prismatic"
  body_a: "carriage"
  anchor { z: 1 }
  axis { x: 2 }
  limits { lower: -0.5 upper: 1.5 }
  damping: 3
  friction: 0.5
}
)pb";
  SceneSpec scene;
  ASSERT_TRUE(ParseSceneText(kSlider, "slider.pbtxt", &scene).ok());
  World world;
  const Status st = BuildWorld(scene, &world);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(world.joints().size(), 1u);
  const Joint& j = world.joints()[0];
  EXPECT_EQ(j.kind, JointKind::kPrismatic);
  EXPECT_TRUE(j.axis_a.isApprox(Vec3::UnitX()));
  EXPECT_TRUE(j.limited);
  EXPECT_EQ(j.lower, -0.5);
  EXPECT_EQ(j.upper, 1.5);
  EXPECT_EQ(j.damping, 3.0);
  EXPECT_EQ(j.friction, 0.5);
}

// Verifies that a joint naming a missing or ambiguous body, or with a bad
// field, is refused with the file, line and field, and the world is left as
// it was.
TEST(SceneJoints, BadJointsNameLineAndFieldAndLeaveTheWorld) {
  const struct {
    const char* joint;
    const char* message;
  } cases[] = {
      {"joints { kind: \"ball\" body_a: \"nobody\" }",
       "s.pbtxt:3: joints[0]: body_a \"nobody\" must name exactly one body, no body has this name"},
      {"joints { kind: \"ball\" body_a: \"twin\" }",
       "s.pbtxt:3: joints[0]: body_a \"twin\" must name exactly one body, 2 bodies have it"},
      {"joints { kind: \"ball\" body_a: \"solo\" body_b: \"solo\" }",
       "s.pbtxt:3: joints[0]: body_b must differ from body_a: a body cannot be jointed to itself (id 3)"},
      {"joints { kind: \"distance\" body_a: \"solo\" length: 0 }",
       "s.pbtxt:3: joints[0]: length must be a finite number > 0, got 0"},
      {"joints { kind: \"slider\" body_a: \"solo\" }",
       "s.pbtxt:3: joints[0]: kind must be one of distance, ball, hinge, fixed, prismatic, got \"slider\""},
      {"joints { kind: \"prismatic\" body_a: \"solo\" axis { x: 1 } limits { lower: 1 upper: -1 } }",
       "s.pbtxt:3: joints[0]: limits must have lower <= upper, got lower 1 > upper -1"},
      {"joints { kind: \"prismatic\" body_a: \"solo\" axis { x: 1 } damping: -2 }",
       "s.pbtxt:3: joints[0]: damping must be a finite number >= 0, got -2"},
      {"joints { kind: \"ball\" body_a: \"solo\" friction: 1 }",
       "s.pbtxt:3: joints[0]: friction applies to hinge and prismatic joints only, not ball (got 1)"},
      {"joints { kind: \"hinge\" body_a: \"solo\" axis { } }",
       "s.pbtxt:3: joints[0]: axis must be a finite nonzero vector, got (0, 0, 0)"},
  };
  for (const auto& c : cases) {
    SceneSpec scene;
    const std::string text = std::string("bodies { name: \"twin\" sphere { radius: 0.1 } }\n") +
                             "bodies { name: \"twin\" sphere { radius: 0.1 } position { x: 1 } }\n" + c.joint +
                             "\nbodies { name: \"solo\" sphere { radius: 0.1 } position { x: 2 } }\n";
    Status st = ParseSceneText(text, "s.pbtxt", &scene);
    if (st.ok()) {
      World world;
      world.gravity = Vec3(0, 0, -1);
      const uint64_t before = HashWorldState(world);
      st = BuildWorld(scene, &world);
      EXPECT_EQ(HashWorldState(world), before);
      EXPECT_EQ(world.gravity, Vec3(0, 0, -1));
    }
    ASSERT_FALSE(st.ok()) << c.joint;
    EXPECT_EQ(st.message(), c.message);
  }
}

}  // namespace
}  // namespace contactsim
