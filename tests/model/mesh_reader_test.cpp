// Tests of the mesh reader against meshes with known corners
// (tests/model/data): STL, OBJ and a COLLADA file in centimetres with a
// node transform.
#include "service/model/mesh_reader.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/model/model_test_util.h"

namespace contactsim::model {
namespace {

using testing::DataDir;

// Vertices are read as floats by assimp: 1e-6 relative is float rounding.
constexpr double kFloatTol = 1e-6;

bool Contains(const std::vector<Vec3>& vs, const Vec3& p) {
  return std::any_of(vs.begin(), vs.end(), [&](const Vec3& v) { return (v - p).norm() < kFloatTol; });
}

// Verifies that an STL cube gives its 8 corners once each (shared corners
// merged), scaled per axis.
TEST(MeshReaderTest, StlCubeGivesEightScaledCorners) {
  std::vector<Vec3> vs;
  const Status st = ReadMeshVertices(DataDir() + "/cube.stl", Vec3(0.1, 0.2, 0.3), ReadLimits{}, &vs);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(vs.size(), 8u);
  for (double x : {-0.05, 0.05}) {
    for (double y : {-0.1, 0.1}) {
      for (double z : {-0.15, 0.15}) EXPECT_TRUE(Contains(vs, Vec3(x, y, z))) << x << " " << y << " " << z;
    }
  }
}

// Verifies that an OBJ tetrahedron gives its 4 corners, with a negative
// scale (a mirrored mesh) applied too.
TEST(MeshReaderTest, ObjTetrahedronGivesItsCorners) {
  std::vector<Vec3> vs;
  const Status st = ReadMeshVertices(DataDir() + "/tetra.obj", Vec3(-1, 1, 1), ReadLimits{}, &vs);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(vs.size(), 4u);
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3)}) EXPECT_TRUE(Contains(vs, p));
}

// Verifies that a COLLADA file's <unit meter="0.01"> and node translation
// are applied (corners in metres, moved 0.5 m along x) and that its Z_UP
// axis does not rotate the vertices.
TEST(MeshReaderTest, ColladaUnitAndNodeTransformAreApplied) {
  std::vector<Vec3> vs;
  const Status st = ReadMeshVertices(DataDir() + "/tetra_cm.dae", Vec3::Ones(), ReadLimits{}, &vs);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(vs.size(), 4u);
  for (const Vec3& p : {Vec3(0.5, 0, 0), Vec3(1.5, 0, 0), Vec3(0.5, 2, 0), Vec3(0.5, 0, 3)}) {
    EXPECT_TRUE(Contains(vs, p)) << p.transpose();
  }
}

// Verifies that a missing file, a file that is no mesh, and the vertex and
// byte limits fail with the path in the message.
TEST(MeshReaderTest, BadFilesAndLimitsAreRefused) {
  std::vector<Vec3> vs;
  Status st = ReadMeshVertices(DataDir() + "/no_such.stl", Vec3::Ones(), ReadLimits{}, &vs);
  EXPECT_EQ(st.code(), StatusCode::kNotFound);
  EXPECT_NE(st.message().find("no_such.stl"), std::string::npos) << st.message();

  st = ReadMeshVertices(DataDir() + "/package.xml", Vec3::Ones(), ReadLimits{}, &vs);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << st.message();
  EXPECT_NE(st.message().find("package.xml"), std::string::npos) << st.message();

  // the limit counts distinct corners: the cube's 8, not the 36 its
  // twelve triangles repeat
  ReadLimits few;
  few.max_mesh_vertices = 7;
  st = ReadMeshVertices(DataDir() + "/cube.stl", Vec3::Ones(), few, &vs);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("max_mesh_vertices"), std::string::npos) << st.message();
  few.max_mesh_vertices = 8;
  EXPECT_TRUE(ReadMeshVertices(DataDir() + "/cube.stl", Vec3::Ones(), few, &vs).ok());

  ReadLimits small;
  small.max_mesh_bytes = 100;
  st = ReadMeshVertices(DataDir() + "/cube.stl", Vec3::Ones(), small, &vs);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("max_mesh_bytes"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace contactsim::model
