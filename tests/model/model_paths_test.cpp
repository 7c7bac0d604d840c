// Tests of the model search paths and URI resolution (model_paths.h) on the
// fixture folders and on temporary package trees.
#include "service/model/model_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tests/model/model_test_util.h"

namespace contactsim::model {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;

// A fresh folder under the test temp dir holding `files` (relative paths).
fs::path MakeTree(const std::string& name, const std::vector<std::pair<std::string, std::string>>& files) {
  const fs::path root = fs::temp_directory_path() / ("contactsim_model_paths_" + name);
  fs::remove_all(root);
  for (const auto& [rel, text] : files) {
    fs::create_directories((root / rel).parent_path());
    std::ofstream(root / rel) << text;
  }
  return root;
}

// Verifies that the list is flags, then config, then the variables in
// kModelPathVariables' order whatever order they are given in, with
// ':'-separated values split, empty entries dropped and repeats kept once.
TEST(ModelPathsTest, SourcesAreOrderedFlagsConfigThenVariables) {
  const ModelPaths p = MakeModelPaths({"/flag", ""}, {"/config", "/flag"},
                                      {{"SDF_PATH", "/sdf"},
                                       {"GZ_SIM_RESOURCE_PATH", "/gz1::/gz2"},
                                       {"ROS_PACKAGE_PATH", "/ros:/config"},
                                       {"IGN_GAZEBO_RESOURCE_PATH", "/ign"}});
  const std::vector<std::string> want = {"/flag", "/config", "/ros", "/gz1", "/gz2", "/ign", "/sdf"};
  EXPECT_EQ(p.directories, want);
}

// Verifies that the environment reader returns the set variables in
// precedence order and ignores others.
TEST(ModelPathsTest, EnvironmentIsReadInPrecedenceOrder) {
  setenv("SDF_PATH", "/s", 1);
  setenv("ROS_PACKAGE_PATH", "/r1:/r2", 1);
  unsetenv("GZ_SIM_RESOURCE_PATH");
  unsetenv("IGN_GAZEBO_RESOURCE_PATH");
  const auto env = ModelPathEnvironment();
  ASSERT_EQ(env.size(), 2u);
  EXPECT_EQ(env[0], std::make_pair(std::string("ROS_PACKAGE_PATH"), std::string("/r1:/r2")));
  EXPECT_EQ(env[1], std::make_pair(std::string("SDF_PATH"), std::string("/s")));
  EXPECT_EQ(MakeModelPaths({}, {}, env).directories, (std::vector<std::string>{"/r1", "/r2", "/s"}));
  unsetenv("SDF_PATH");
  unsetenv("ROS_PACKAGE_PATH");
}

// Verifies relative, absolute and file:// names inside a model file.
TEST(ModelPathsTest, RelativeAbsoluteAndFileUris) {
  std::string out;
  ASSERT_TRUE(ResolveModelUri("tetra.obj", DataDir(), ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/tetra.obj");
  ASSERT_TRUE(ResolveModelUri("../data/./cube.stl", DataDir(), ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");
  ASSERT_TRUE(ResolveModelUri(DataDir() + "/cube.stl", "/elsewhere", ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");
  ASSERT_TRUE(ResolveModelUri("file://" + DataDir() + "/cube.stl", "", ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");
  // inline text has no directory: a relative name is looked up in the search list
  ASSERT_TRUE(ResolveModelUri("cube.stl", "", ModelPaths{{"/nowhere", DataDir()}}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");
}

// Verifies package:// by folder name, by package.xml <name> below a search
// directory, and by the package the model file sits in.
TEST(ModelPathsTest, PackageUrisResolveAsRosAndDrakeDo) {
  std::string out;
  const ModelPaths packages{{DataDir() + "/packages"}};
  ASSERT_TRUE(ResolveModelUri("package://gripper_dir/meshes/finger.obj", "", packages, &out).ok());
  EXPECT_EQ(out, DataDir() + "/packages/gripper_dir/meshes/finger.obj");
  ASSERT_TRUE(ResolveModelUri("package://gripper_description/meshes/finger.obj", "", packages, &out).ok());
  EXPECT_EQ(out, DataDir() + "/packages/gripper_dir/meshes/finger.obj");
  // no search path: the model file's own package (data/package.xml) and its folder's parents
  ASSERT_TRUE(ResolveModelUri("package://model_test_data/cube.stl", DataDir() + "/models", ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");
  ASSERT_TRUE(ResolveModelUri("package://data/cube.stl", DataDir(), ModelPaths{}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/cube.stl");

  const Status st = ResolveModelUri("package://absent_pkg/x.stl", DataDir(), packages, &out);
  EXPECT_EQ(st.code(), StatusCode::kNotFound);
  EXPECT_NE(st.message().find("package://absent_pkg/x.stl"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find(DataDir() + "/packages"), std::string::npos) << st.message();
}

// Verifies that the first search directory holding a package wins, so the
// flag overrides the config and the config the environment.
TEST(ModelPathsTest, FirstSearchDirectoryWins) {
  const fs::path a = MakeTree("a", {{"pkg/m.stl", "a"}});
  const fs::path b = MakeTree("b", {{"other/package.xml", "<package><name>pkg</name></package>"}, {"other/m.stl", "b"}});
  std::string out;
  ASSERT_TRUE(ResolveModelUri("package://pkg/m.stl", "", MakeModelPaths({a}, {b}, {}), &out).ok());
  EXPECT_EQ(out, (a / "pkg/m.stl").string());
  ASSERT_TRUE(ResolveModelUri("package://pkg/m.stl", "", MakeModelPaths({b}, {a}, {}), &out).ok());
  EXPECT_EQ(out, (b / "other/m.stl").string());
  ASSERT_TRUE(
      ResolveModelUri("package://pkg/m.stl", "", MakeModelPaths({}, {}, {{"ROS_PACKAGE_PATH", b.string() + ":" + a.string()}}), &out)
          .ok());
  EXPECT_EQ(out, (b / "other/m.stl").string());
  fs::remove_all(a);
  fs::remove_all(b);
}

// Verifies model:// against Gazebo's resource path, and that a model file
// names its sibling models without one.
TEST(ModelPathsTest, ModelUrisResolveAsGazeboDoes) {
  std::string out;
  ASSERT_TRUE(ResolveModelUri("model://tetra_model/meshes/tetra.obj", "", ModelPaths{{DataDir() + "/models"}}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/models/tetra_model/meshes/tetra.obj");
  ASSERT_TRUE(
      ResolveModelUri("model://tetra_model/meshes/tetra.obj", DataDir() + "/models/other_model", ModelPaths{}, &out)
          .ok());
  EXPECT_EQ(out, DataDir() + "/models/tetra_model/meshes/tetra.obj");
  EXPECT_EQ(ResolveModelUri("model://absent/x.obj", "", ModelPaths{{DataDir()}}, &out).code(), StatusCode::kNotFound);
}

// Verifies the top-level file lookup and the refusal of other schemes.
TEST(ModelPathsTest, ModelFileAndUnknownSchemes) {
  std::string out;
  ASSERT_TRUE(ResolveModelFile("arm.urdf", ModelPaths{{"/nowhere", DataDir()}}, &out).ok());
  EXPECT_EQ(out, DataDir() + "/arm.urdf");
  const Status st = ResolveModelFile("arm.urdf", ModelPaths{{"/nowhere"}}, &out);
  EXPECT_EQ(st.code(), StatusCode::kNotFound);
  EXPECT_NE(st.message().find("/nowhere/arm.urdf"), std::string::npos) << st.message();
  EXPECT_EQ(ResolveModelUri("https://example.com/a.stl", "", ModelPaths{}, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(ResolveModelUri("", "", ModelPaths{}, &out).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace contactsim::model
