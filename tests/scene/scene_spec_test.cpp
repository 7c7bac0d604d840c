// Tests of scene files: errors name file, line and field; lattices are
// deterministic; a bad scene leaves the world untouched.
#include "service/scene/scene_spec.h"

#include <gtest/gtest.h>

namespace contactsim {
namespace {

// Verifies that a syntax error is reported with file, line and column.
TEST(SceneSpec, SyntaxErrorNamesFileLineAndColumn) {
  SceneSpec scene;
  const Status st = ParseSceneText("gravity { z: -9.81 }\nbodies { sphere { radius: } }\n", "s.pbtxt", &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.message().rfind("s.pbtxt:2:", 0), 0u) << st.message();
}

// Verifies that an unknown field is reported with its line.
TEST(SceneSpec, UnknownFieldNamesTheField) {
  SceneSpec scene;
  const Status st = ParseSceneText("\n\ngravty { z: 1 }\n", "s.pbtxt", &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("s.pbtxt:3:"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("gravty"), std::string::npos) << st.message();
}

// Verifies that a bad body names the file, the body's line, its index and
// name, the field and the value; and that the world is left as it was.
TEST(SceneSpec, BadBodyNamesLineFieldAndValueAndLeavesWorld) {
  SceneSpec scene;
  ASSERT_TRUE(ParseSceneText("bodies { plane { normal { z: 1 } } }\n"
                             "bodies { name: \"ok\" sphere { radius: 0.1 } }\n"
                             "bodies {\n  name: \"bad\"\n  sphere { radius: -0.5 }\n}\n",
                             "s.pbtxt", &scene)
                  .ok());
  World world;
  BodySettings keep;
  keep.radius = 1.0;
  RigidBody b;
  ASSERT_TRUE(CreateBody(keep, Material{}, &b).ok());
  world.AddBody(b);
  const uint64_t before = HashWorldState(world);
  const Status st = BuildWorld(scene, &world);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("s.pbtxt:3: bodies[2] \"bad\": radius must be a finite number > 0, got -0.5"),
            std::string::npos)
      << st.message();
  EXPECT_EQ(HashWorldState(world), before);
}

// Verifies that dt out of range is refused with its line.
TEST(SceneSpec, TimeStepOutOfRangeIsRefused) {
  SceneSpec scene;
  const Status st = ParseSceneText("gravity { z: -9.81 }\ndt: 0.5\n", "s.pbtxt", &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("s.pbtxt:2: dt must be in"), std::string::npos) << st.message();
}

// Verifies that a lattice expands to nx*ny*nz bodies at the given spacing,
// with the same jitter and orientations for the same seed.
TEST(SceneSpec, GridIsDeterministicForASeed) {
  const char* text =
      "grids { prototype { box { half_extents { x: 0.1 y: 0.1 z: 0.1 } } } nx: 3 ny: 2 nz: 4\n"
      "        origin { z: 0.5 } spacing { x: 0.3 y: 0.3 z: 0.3 } jitter: 0.01 random_orientation: true seed: 7 }\n";
  SceneSpec a, b;
  ASSERT_TRUE(ParseSceneText(text, "g.pbtxt", &a).ok());
  ASSERT_TRUE(ParseSceneText(text, "g.pbtxt", &b).ok());
  ASSERT_EQ(a.bodies.size(), 24u);
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].position, b.bodies[i].position);
    EXPECT_EQ(a.bodies[i].orientation, b.bodies[i].orientation);
    EXPECT_NEAR(a.bodies[i].orientation.norm(), 1.0, 1e-12);
  }
  // the last body: (i, j, k) = (2, 1, 3); jitter only in x and y
  EXPECT_NEAR(a.bodies.back().position.x(), 0.6, 0.01 + 1e-12);
  EXPECT_NEAR(a.bodies.back().position.y(), 0.3, 0.01 + 1e-12);
  EXPECT_DOUBLE_EQ(a.bodies.back().position.z(), 0.5 + 0.9);
}

// Verifies that a randomly oriented lattice too tight for any orientation
// (1 m cubes 1 m apart touch in every orientation) is refused with the grid
// named, instead of starting with overlapping bodies.
TEST(SceneSpec, GridTooTightForAnyOrientationIsRefused) {
  const char* text =
      "grids { prototype { box { half_extents { x: 0.5 y: 0.5 z: 0.5 } } } nx: 2 ny: 1 nz: 1\n"
      "        spacing { x: 0.9 } random_orientation: true }\n";
  SceneSpec scene;
  const Status st = ParseSceneText(text, "g.pbtxt", &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("g.pbtxt:1: grids[0]: grids body (1, 0, 0) overlaps a neighbour"), std::string::npos)
      << st.message();
}

// Verifies that a grid's comb joins every body to the one above it and the
// top row along x by ball joints at the midpoints, fixes the top row's
// middle bodies and joins no two of them, and builds into a world.
TEST(SceneSpec, GridCombJoinsColumnsAndTheTopRow) {
  const char* text =
      "grids { prototype { name: \"ball\" sphere { radius: 0.4 } } nx: 5 nz: 3\n"
      "        origin { z: 1 } spacing { x: 1 z: 1 } comb_joints: \"ball\" fixed_top: 3 }\n";
  SceneSpec scene;
  const Status st = ParseSceneText(text, "c.pbtxt", &scene);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(scene.bodies.size(), 15u);
  // columns 5 x 2, the top row 4 less the 2 between anchors
  ASSERT_EQ(scene.joints.size(), 12u);
  int fixed = 0;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const bool anchor = i >= 11 && i <= 13;  // top row (k = 2: bodies 10-14), i = 1..3
    EXPECT_EQ(scene.bodies[i].fixed, anchor) << "body " << i;
    fixed += scene.bodies[i].fixed;
  }
  EXPECT_EQ(fixed, 3);
  // the first joint: (0, 0, 0) up to (0, 0, 1), at their midpoint
  EXPECT_EQ(scene.joints[0].settings.kind, JointKind::kBall);
  EXPECT_EQ(scene.joints[0].body_a, "ball_0");
  EXPECT_EQ(scene.joints[0].body_b, "ball_5");
  EXPECT_EQ(scene.joints[0].settings.anchor, Vec3(0, 0, 1.5));
  World world;
  const Status built = BuildWorld(scene, &world);
  EXPECT_TRUE(built.ok()) << built.message();
  EXPECT_EQ(world.joints().size(), 12u);
}

// Verifies that a comb needs a named prototype and a known joint kind, and
// that fixed_top stays within the row, each refused with the field named.
TEST(SceneSpec, GridCombIsCheckedWithTheFieldNamed) {
  const struct {
    const char* grid;
    const char* message;
  } cases[] = {
      {"prototype { sphere { radius: 0.4 } } nx: 2 comb_joints: \"ball\"", "comb_joints needs a named prototype"},
      {"prototype { name: \"b\" sphere { radius: 0.4 } } nx: 2 comb_joints: \"hinge\"",
       "comb_joints must be \"ball\" or empty, got \"hinge\""},
      {"prototype { name: \"b\" sphere { radius: 0.4 } } nx: 2 fixed_top: 3",
       "fixed_top must be between 0 and nx = 2, got 3"},
  };
  for (const auto& c : cases) {
    SceneSpec scene;
    const Status st = ParseSceneText(std::string("grids { ") + c.grid + " }\n", "c.pbtxt", &scene);
    ASSERT_FALSE(st.ok()) << c.grid;
    EXPECT_NE(st.message().find(std::string("c.pbtxt:1: grids[0]: ") + c.message), std::string::npos)
        << st.message();
  }
}

// Verifies that the default scene shipped in config/ loads and builds.
TEST(SceneSpec, ShippedScenesLoad) {
  for (const char* name : {"default", "joints"}) {
    SceneSpec scene;
    const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + name + ".pbtxt";
    const Status st = LoadSceneFile(path, &scene);
    ASSERT_TRUE(st.ok()) << st.message();
    World world;
    ASSERT_TRUE(BuildWorld(scene, &world).ok());
    EXPECT_GT(world.bodies().size(), 3u);
  }
}

}  // namespace
}  // namespace contactsim

namespace contactsim {
namespace {

// Verifies that a body's filter and a joint's collide_connected are read
// from a scene file (hex masks included; a grid's prototype passes its
// filter to every body), and that bodies and joints without them get the
// defaults.
TEST(SceneSpec, CollisionFiltersAndCollideConnectedAreRead) {
  SceneSpec scene;
  const std::string text =
      "bodies { name: \"a\" sphere { radius: 0.1 } position { z: 1 }\n"
      "         filter { category: 2 mask: 0xFFFFFFFE group: -3 } }\n"
      "bodies { name: \"b\" sphere { radius: 0.1 } position { z: 1.2 } }\n"
      "grids { prototype { box { half_extents { x: 0.1 y: 0.1 z: 0.1 } } filter { group: 4 } }\n"
      "        nx: 2 spacing { x: 1 } origin { x: 3 z: 1 } }\n"
      "joints { kind: \"ball\" body_a: \"a\" body_b: \"b\" anchor { z: 1.1 } collide_connected: true }\n"
      "joints { kind: \"ball\" body_a: \"b\" anchor { z: 2 } }\n";
  ASSERT_TRUE(ParseSceneText(text, "f.pbtxt", &scene).ok());
  World world;
  ASSERT_TRUE(BuildWorld(scene, &world).ok());
  const RigidBody& a = world.bodies()[0];
  EXPECT_EQ(a.collision_category, 2u);
  EXPECT_EQ(a.collision_mask, 0xFFFFFFFEu);
  EXPECT_EQ(a.collision_group, -3);
  EXPECT_TRUE(HasDefaultFilter(world.bodies()[1]));
  ASSERT_EQ(world.bodies().size(), 4u);
  EXPECT_EQ(world.bodies()[2].collision_group, 4);
  EXPECT_EQ(world.bodies()[3].collision_group, 4);
  ASSERT_EQ(world.joints().size(), 2u);
  EXPECT_TRUE(world.joints()[0].collide_connected);
  EXPECT_FALSE(world.joints()[1].collide_connected);
  EXPECT_TRUE(world.joined_pairs().empty()) << "the only joint between two bodies lets them touch";
}

}  // namespace
}  // namespace contactsim
