// Tests of reading a model file by its format: the top element picks the
// reader, the file is found on the search paths, and size limits hold.
#include "service/model/model_file.h"

#include <gtest/gtest.h>

#include "tests/model/model_test_util.h"

namespace contactsim::model {
namespace {

using testing::DataDir;

// Verifies that <robot> is read as URDF and <sdf> as SDF, from the search
// paths when the name is relative.
TEST(ModelFileTest, TopElementPicksTheReader) {
  const ModelPaths paths{{DataDir(), DataDir() + "/models"}};
  ModelDescription urdf, sdf;
  Status st = ReadModelFile("arm.urdf", paths, ReadLimits{}, &urdf);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(urdf.name, "test_arm");
  EXPECT_EQ(urdf.source, DataDir() + "/arm.urdf");
  st = ReadModelFile("arm.sdf", paths, ReadLimits{}, &sdf);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(sdf.name, "sdf_arm");
  ModelFormat format;
  ASSERT_TRUE(DetectModelFormat("<?xml version=\"1.0\"?><!-- c --><robot name=\"r\"/>", "x", &format).ok());
  EXPECT_EQ(format, ModelFormat::kUrdf);
}

// Verifies that a Gazebo model folder named by model:// stands for the SDF
// file its model.config names.
TEST(ModelFileTest, ModelFolderReadsTheFileItsConfigNames) {
  ModelDescription d;
  const Status st = ReadModelFile("model://tetra_model", ModelPaths{{DataDir() + "/models"}}, ReadLimits{}, &d);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(d.name, "tetra");
  EXPECT_EQ(d.source, DataDir() + "/models/tetra_model/tetra.sdf");
  const Status folder = ReadModelFile("packages", ModelPaths{{DataDir()}}, ReadLimits{}, &d);
  EXPECT_EQ(folder.code(), StatusCode::kNotFound);
  EXPECT_NE(folder.message().find("without model.config or model.sdf"), std::string::npos) << folder.message();
}

// Verifies the refusals: neither format, malformed XML, a missing file, a
// file over the size limit (checked before it is read).
TEST(ModelFileTest, BadFilesAreRefused) {
  ModelDescription d;
  Status st = ReadModelText("<mujoco/>", "<inline>", ModelPaths{}, ReadLimits{}, &d);
  EXPECT_NE(st.message().find("neither URDF"), std::string::npos) << st.message();
  st = ReadModelText("<robot>\n<link>", "<inline>", ModelPaths{}, ReadLimits{}, &d);
  EXPECT_NE(st.message().find("malformed XML at line"), std::string::npos) << st.message();
  st = ReadModelFile("absent.urdf", ModelPaths{{DataDir()}}, ReadLimits{}, &d);
  EXPECT_EQ(st.code(), StatusCode::kNotFound);
  ReadLimits small;
  small.max_file_bytes = 1000;
  st = ReadModelFile(DataDir() + "/arm.urdf", ModelPaths{}, small, &d);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("arm.urdf"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace contactsim::model
