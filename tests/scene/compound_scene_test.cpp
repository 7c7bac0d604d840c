// Tests of compound bodies and explicit mass properties in scene files and
// snapshots: a scene's compound and inertial build the body the settings
// would, and a snapshot keeps the children, the frame's origin and the
// explicit inertia exactly, so a restored run continues bit for bit.
#include <gtest/gtest.h>

#include "service/contact/contact_method_registry.h"
#include "service/physics/body_settings.h"
#include "service/proto/snapshot.pb.h"
#include "service/scene/scene_spec.h"
#include "service/scene/snapshot.h"

namespace contactsim {
namespace {

constexpr char kScene[] = R"(
bodies { name: "ground" plane { normal { z: 1 } } }
bodies {
  name: "table"
  compound {
    parts { box { half_extents { x: 0.2 y: 0.15 z: 0.015 } } position { z: 0.2 } }
    parts { box { half_extents { x: 0.015 y: 0.015 z: 0.1 } } position { x: 0.17 y: 0.12 z: 0.085 } }
    parts { box { half_extents { x: 0.015 y: 0.015 z: 0.1 } } position { x: -0.17 y: 0.12 z: 0.085 } }
    parts { box { half_extents { x: 0.015 y: 0.015 z: 0.1 } } position { x: 0.17 y: -0.12 z: 0.085 } }
    parts { box { half_extents { x: 0.015 y: 0.015 z: 0.1 } } position { x: -0.17 y: -0.12 z: 0.085 } }
  }
  position { z: 0.02 }
  mass: 3
}
bodies {
  name: "link"
  compound {
    parts { capsule { radius: 0.03 half_length: 0.1 } position { x: 0.05 } orientation { w: 0.8 x: 0.6 } }
    parts { sphere { radius: 0.05 } position { x: -0.1 } }
    parts { convex { points { } points { x: 0.1 } points { y: 0.1 } points { z: 0.1 } } position { y: 0.1 } }
  }
  position { x: 1 z: 0.5 }
  angular_velocity { x: 1 y: 2 z: 3 }
  mass: 1.5
  center_of_mass { x: 0.01 y: 0.02 }
  inertia { ixx: 0.004 iyy: 0.005 izz: 0.003 ixy: 0.0002 ixz: -0.0001 iyz: 0.0003 }
}
)";

World BuildScene() {
  SceneSpec scene;
  Status st = ParseSceneText(kScene, "compound.pbtxt", &scene);
  EXPECT_TRUE(st.ok()) << st.message();
  World world;
  st = BuildWorld(scene, &world);
  EXPECT_TRUE(st.ok()) << st.message();
  return world;
}

// Verifies the scene's compounds: the table's five parts about its centre
// of mass, the link's explicit centre of mass and inertia as given.
TEST(CompoundSceneTest, SceneCompoundsBuildTheirBodies) {
  const World world = BuildScene();
  ASSERT_EQ(world.bodies().size(), 3u);
  const RigidBody& table = world.bodies()[1];
  ASSERT_EQ(table.shape.type, ShapeType::kCompound);
  EXPECT_EQ(table.shape.compound->children.size(), 5u);
  EXPECT_NEAR(table.mass, 3.0, 1e-15);
  const RigidBody& link = world.bodies()[2];
  EXPECT_TRUE(link.frame_origin.isApprox(Vec3(-0.01, -0.02, 0), 1e-15));
  EXPECT_TRUE(link.x.isApprox(Vec3(1.01, 0.02, 0.5), 1e-15));
  EXPECT_TRUE(link.explicit_inertia);
  EXPECT_NEAR(link.inertia_body(0, 1), 0.0002, 1e-18);
  EXPECT_NEAR(link.inertia_body(2, 1), 0.0003, 1e-18);
}

// Verifies a scene with a bad part is refused naming it.
TEST(CompoundSceneTest, BadPartsAreRefusedByName) {
  SceneSpec scene;
  ASSERT_TRUE(ParseSceneText("bodies { compound { parts { sphere { radius: -1 } } } }\n", "bad.pbtxt", &scene).ok());
  World world;
  const Status st = BuildWorld(scene, &world);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("parts[0].radius"), std::string::npos) << st.message();
}

// Verifies, for every method that takes compounds, that a snapshot keeps
// them exactly: the restored run matches the original's hashes and ends
// with the same snapshot bytes; the loaded bodies hold the same children,
// frame origins and explicit inertia.
TEST(CompoundSceneTest, SnapshotsKeepCompoundsExactly) {
  for (const ContactMethodEntry& entry : ContactMethodTable()) {
    if (!entry.contract.compound_bodies) continue;
    SCOPED_TRACE(entry.name);
    World world = BuildScene();
    std::unique_ptr<ContactMethod> made;
    ASSERT_TRUE(CreateContactMethod(entry.name, &made).ok());
    std::shared_ptr<ContactMethod> method(std::move(made));
    CollisionDetector detector;
    ContactSet contacts;
    for (int i = 0; i < 60; ++i) method->Step(world, detector, &contacts);
    proto::Snapshot saved;
    SaveSnapshot(world, *method, &saved);
    proto::Snapshot parsed;
    ASSERT_TRUE(parsed.ParseFromString(saved.SerializeAsString()));
    World restored;
    std::shared_ptr<ContactMethod> restored_method;
    const Status st = LoadSnapshot(parsed, &restored, &restored_method);
    ASSERT_TRUE(st.ok()) << st.message();
    for (size_t k = 0; k < world.bodies().size(); ++k) {
      const RigidBody& a = world.bodies()[k];
      const RigidBody& b = restored.bodies()[k];
      EXPECT_EQ(a.frame_origin, b.frame_origin);
      EXPECT_EQ(a.explicit_inertia, b.explicit_inertia);
      EXPECT_EQ(a.shape.type, b.shape.type);
      if (a.shape.type != ShapeType::kCompound) continue;
      ASSERT_EQ(a.shape.compound->children.size(), b.shape.compound->children.size());
      for (size_t c = 0; c < a.shape.compound->children.size(); ++c) {
        EXPECT_EQ(a.shape.compound->children[c].position, b.shape.compound->children[c].position);
        EXPECT_EQ(a.shape.compound->children[c].orientation.coeffs(), b.shape.compound->children[c].orientation.coeffs());
      }
    }
    CollisionDetector again_detector;
    ContactSet again_contacts;
    for (int i = 0; i < 60; ++i) {
      method->Step(world, detector, &contacts);
      restored_method->Step(restored, again_detector, &again_contacts);
      ASSERT_EQ(HashWorldState(world), HashWorldState(restored)) << "diverged at step " << 61 + i;
    }
  }
}

// Verifies a snapshot whose compound holds a plane child is refused.
TEST(CompoundSceneTest, DamagedCompoundSnapshotsAreRefused) {
  World world = BuildScene();
  std::unique_ptr<ContactMethod> method;
  ASSERT_TRUE(CreateContactMethod("impulse", &method).ok());
  proto::Snapshot saved;
  SaveSnapshot(world, *method, &saved);
  proto::Snapshot plane_child = saved;
  plane_child.mutable_bodies(1)->mutable_shape()->mutable_children(0)->mutable_shape()->set_type(
      static_cast<int>(ShapeType::kPlane));
  World target;
  std::shared_ptr<ContactMethod> out;
  Status st = LoadSnapshot(plane_child, &target, &out);
  EXPECT_NE(st.message().find("must be a sphere, box, capsule or convex, got plane"), std::string::npos) << st.message();
  proto::Snapshot no_children = saved;
  no_children.mutable_bodies(1)->mutable_shape()->clear_children();
  st = LoadSnapshot(no_children, &target, &out);
  EXPECT_NE(st.message().find("compound must hold 1 to 64 children, got 0"), std::string::npos) << st.message();
  EXPECT_TRUE(target.bodies().empty());
}

}  // namespace
}  // namespace contactsim
