// Tests of robot models listed in scene files: read with the scene, found
// beside it, added after its bodies as a whole, and a bad one named by the
// scene's line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "service/scene/scene_spec.h"

namespace contactsim {
namespace {

// A two-sphere pendulum whose spheres sit at their links' centres of mass
// with the solid sphere's inertia (0.4 m r^2).
constexpr char kPendulum[] = R"(<robot name="pendulum">
  <link name="top">
    <inertial><mass value="2"/><inertia ixx="0.008" iyy="0.008" izz="0.008" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <link name="bob">
    <inertial><mass value="1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="swing" type="continuous">
    <parent link="top"/><child link="bob"/><origin xyz="0 0 -0.5"/><axis xyz="0 1 0"/>
  </joint>
</robot>
)";

class SceneModelsTest : public ::testing::Test {
 protected:
  SceneModelsTest() {
    dir_ = std::filesystem::temp_directory_path() / ("contactsim-scene-models-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "pendulum.urdf") << kPendulum;
  }
  ~SceneModelsTest() override { std::filesystem::remove_all(dir_); }
  std::string Scene() const { return (dir_ / "scene.pbtxt").string(); }
  std::filesystem::path dir_;
};

// Verifies that a scene's model is found beside the scene file, placed at
// its pose with a fixed base, and added after the scene's own body.
TEST_F(SceneModelsTest, ModelsAreAddedAfterTheBodies) {
  SceneSpec scene;
  const Status st = ParseSceneText(R"(
    bodies { name: "floor" plane { normal { z: 1 } } fixed: true }
    models { path: "pendulum.urdf" name: "p" position { z: 2 } fixed_base: true }
  )", Scene(), &scene);
  ASSERT_TRUE(st.ok()) << st.message();
  World world;
  const Status built = BuildWorld(scene, &world);
  ASSERT_TRUE(built.ok()) << built.message();
  ASSERT_EQ(world.bodies().size(), 3u);
  ASSERT_EQ(world.models.size(), 1u);
  const ModelRecord& m = world.models[0];
  EXPECT_EQ(m.name, "p");
  EXPECT_EQ(m.links[0].body, 2);
  EXPECT_FALSE(world.Find(2)->IsDynamic());
  EXPECT_LT((world.Find(3)->x - Vec3(0, 0, 1.5)).norm(), 1e-15);
  ASSERT_EQ(world.joints().size(), 1u);
  EXPECT_EQ(m.joints[0].joint, world.joints()[0].id);
}

// Verifies that a model file that cannot be found is an error of the
// scene's, naming the line and the entry.
TEST_F(SceneModelsTest, AMissingModelNamesTheSceneLine) {
  SceneSpec scene;
  const Status st = ParseSceneText("models { path: \"nowhere.urdf\" }\n", Scene(), &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("scene.pbtxt:1: models[0]: "), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("nowhere.urdf"), std::string::npos) << st.message();
}

// Verifies that a model's hull budget below four is an error of the
// scene's, naming the line, the entry and the value.
TEST_F(SceneModelsTest, AHullBudgetBelowFourNamesTheSceneLine) {
  SceneSpec scene;
  const Status st = ParseSceneText("models { path: \"pendulum.urdf\" max_hull_vertices: 2 }\n", Scene(), &scene);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("scene.pbtxt:1: models[0]: max_hull_vertices must be -1 (every vertex), 0 (the "
                              "default, 64) or at least 4, got 2"),
            std::string::npos)
      << st.message();
  ASSERT_TRUE(ParseSceneText("models { path: \"pendulum.urdf\" max_hull_vertices: -1 }\n", Scene(), &scene).ok());
}

}  // namespace
}  // namespace contactsim
