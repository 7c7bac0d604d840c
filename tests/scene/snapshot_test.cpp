// Tests of snapshots: engine state -> binary protobuf -> engine state, and
// that a run restored from a snapshot continues bit for bit.
#include "service/scene/snapshot.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>

#include "service/contact/sleep/island_sleep.h"
#include "service/physics/body_settings.h"
#include "tests/contact/test_bodies.h"
#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::AddValidBody;

// A scene with every kind of state a snapshot must carry: resting and
// sliding contact with friction (penalty anchors), a stack, a tumbling
// convex hull, a capsule, a timed wrench that outlives the snapshot step,
// a pendulum and a hinge with limits.
World MixedWorld() {
  World w;
  AddGround(w, 0.2, 0.6);
  AddBox(w, 0.1, Vec3(0, 0, 0.1), 0.1, 0.6, Vec3(0.4, 0, 0));  // slides, then sticks
  AddBox(w, 0.1, Vec3(0.5, 0, 0.1), 0.1, 0.6);
  AddBox(w, 0.1, Vec3(0.5, 0, 0.31), 0.1, 0.6);               // stacked
  AddSphere(w, 0.1, Vec3(-0.5, 0, 0.4), 0.5, 0.4, Vec3(0, 0.3, 0));
  BodySettings convex;
  convex.shape = ShapeType::kConvex;
  convex.points = {{0.1, 0, 0}, {-0.1, 0, 0}, {0, 0.12, 0}, {0, -0.1, 0}, {0, 0, 0.15}, {0.03, 0.02, -0.1}};
  convex.position = Vec3(0, 0.6, 0.5);
  convex.angular_velocity = Vec3(1, 2, 0.5);
  AddValidBody(w, convex);
  BodySettings capsule;
  capsule.shape = ShapeType::kCapsule;
  capsule.radius = 0.05;
  capsule.half_length = 0.1;
  capsule.position = Vec3(0, -0.6, 0.3);
  capsule.orientation = Eigen::Vector4d(0.9, 0.3, 0.1, 0);
  AddValidBody(w, capsule);
  w.AddWrench({2, Vec3(3, 1, 0), Vec3(0, 0, 0.2), 0.5});
  // joints are world state too: a swinging pendulum and a door on a hinge
  // with limits
  JointId id = 0;
  JointSettings rod;
  rod.kind = JointKind::kDistance;
  rod.body_a = AddSphere(w, 0.05, Vec3(1.5, 0, 1.0), 0.5, 0.4);
  rod.anchor = Vec3(1.2, 0, 1.5);
  EXPECT_TRUE(w.AddJoint(rod, &id).ok());
  JointSettings hinge;
  hinge.kind = JointKind::kHinge;
  hinge.body_a = AddBox(w, Vec3(0.3, 0.02, 0.2), Vec3(-1.3, 0, 0.5), 0.1, 0.6, Vec3(0, 0.5, 0));
  hinge.anchor = Vec3(-1.6, 0, 0.5);
  hinge.axis = Vec3::UnitZ();
  hinge.limits = std::make_pair(-0.4, 0.4);
  EXPECT_TRUE(w.AddJoint(hinge, &id).ok());
  return w;
}

std::shared_ptr<ContactMethod> Method(const std::string& name) { return testing_util::NewMethod(name); }

// Hash of the world after each of `n` steps, with a fresh detector.
std::vector<uint64_t> RunSteps(World& w, ContactMethod& method, int n) {
  CollisionDetector detector;
  return testing_util::StepHashes(w, method, detector, n);
}

std::string Bytes(const World& w, const ContactMethod& m) {
  proto::Snapshot s;
  SaveSnapshot(w, m, &s);
  return s.SerializeAsString();
}

// Verifies, for every registered contact method, that a run restored from
// a snapshot taken at step k reproduces the original's state hash at every
// step up to n, and ends with an identical snapshot (caches included).
TEST(SnapshotTest, RestoredRunMatchesTheOriginalBitForBitForEveryMethod) {
  constexpr int kSnapshotStep = 60, kLastStep = 200;
  for (const std::string& name : ContactMethodNames()) {
    SCOPED_TRACE(name);
    World world = MixedWorld();
    auto method = Method(name);
    RunSteps(world, *method, kSnapshotStep);
    proto::Snapshot saved;
    SaveSnapshot(world, *method, &saved);
    const std::vector<uint64_t> original = RunSteps(world, *method, kLastStep - kSnapshotStep);
    const std::string original_end = Bytes(world, *method);

    proto::Snapshot parsed;
    ASSERT_TRUE(parsed.ParseFromString(saved.SerializeAsString()));
    World restored;
    std::shared_ptr<ContactMethod> restored_method;
    const Status st = LoadSnapshot(parsed, &restored, &restored_method);
    ASSERT_TRUE(st.ok()) << st.message();
    EXPECT_EQ(restored.step, kSnapshotStep);
    const std::vector<uint64_t> again = RunSteps(restored, *restored_method, kLastStep - kSnapshotStep);
    ASSERT_EQ(again.size(), original.size());
    for (size_t i = 0; i < original.size(); ++i) {
      ASSERT_EQ(again[i], original[i]) << "first divergence at step " << kSnapshotStep + 1 + i;
    }
    EXPECT_EQ(Bytes(restored, *restored_method), original_end);
  }
}

// Hash of a world stepped with sleeping islands after each of `n` steps,
// and the fewest bodies asleep after any of them.
std::vector<uint64_t> RunSleeping(World& w, ContactMethod& method, int n, int* fewest_asleep) {
  CollisionDetector detector;
  ContactSet contacts;
  IslandSleep sleep;
  std::vector<uint64_t> hashes;
  *fewest_asleep = static_cast<int>(w.bodies().size());
  for (int i = 0; i < n; ++i) {
    sleep.Step(w, method, detector, &contacts);
    hashes.push_back(HashWorldState(w));
    *fewest_asleep = std::min(*fewest_asleep, w.SleepingCount());
  }
  return hashes;
}

// Verifies, for every registered contact method, that a snapshot taken
// while a stack sleeps restores its sleep state (rest timers, island
// labels, settings) and that the restored run matches the original bit for
// bit, through a ball that falls onto the stack and wakes it, and that two
// runs of the same world give the same hashes.
TEST(SnapshotTest, RestoredRunReproducesSleepingBitForBitForEveryMethod) {
  constexpr int kAfter = 480;
  for (const std::string& name : ContactMethodNames()) {
    SCOPED_TRACE(name);
    World world;
    world.sleep.enabled = true;
    AddGround(world, 0.0, 0.6);
    AddBox(world, 0.1, Vec3(0, 0, 0.101), 0.0, 0.6);
    AddBox(world, 0.1, Vec3(0, 0, 0.302), 0.0, 0.6);
    AddSphere(world, 0.05, Vec3(0.05, 0, 12.0), 0.0, 0.6);  // lands after about 1.5 s
    auto method = Method(name);
    CollisionDetector detector;
    ContactSet contacts;
    IslandSleep sleep;
    while (world.SleepingCount() < 2 && world.time < 1.4) sleep.Step(world, *method, detector, &contacts);
    ASSERT_EQ(world.SleepingCount(), 2) << "the stack did not sleep by t = " << world.time;
    proto::Snapshot saved;
    SaveSnapshot(world, *method, &saved);
    int fewest = 0;
    const std::vector<uint64_t> original = RunSleeping(world, *method, kAfter, &fewest);
    EXPECT_EQ(fewest, 0) << "the ball never woke the stack";

    World restored;
    std::shared_ptr<ContactMethod> restored_method;
    const Status st = LoadSnapshot(saved, &restored, &restored_method);
    ASSERT_TRUE(st.ok()) << st.message();
    EXPECT_TRUE(restored.sleep.enabled);
    EXPECT_EQ(restored.SleepingCount(), 2);
    const std::vector<uint64_t> again = RunSleeping(restored, *restored_method, kAfter, &fewest);
    for (size_t i = 0; i < original.size(); ++i) {
      ASSERT_EQ(again[i], original[i]) << "first divergence " << i + 1 << " steps after the snapshot";
    }
    EXPECT_EQ(Bytes(restored, *restored_method), Bytes(world, *method));
  }
}

// Verifies that a prismatic joint with limits, damping and friction, and a
// hinge with damping and friction, come back from a snapshot with every
// field, and the restored run matches the original bit for bit.
TEST(SnapshotTest, SlidersAndJointDynamicsRoundTrip) {
  World world;
  JointId id = 0;
  JointSettings slider;
  slider.kind = JointKind::kPrismatic;
  slider.body_a = AddBox(world, 0.1, Vec3(0, 0, 1), 0.0, 0.5);
  slider.anchor = Vec3(0, 0, 1);
  slider.axis = Vec3(1, 0, 1);
  slider.limits = std::make_pair(-0.2, 0.3);
  slider.damping = 0.7;
  slider.friction = 0.4;
  ASSERT_TRUE(world.AddJoint(slider, &id).ok());
  JointSettings hinge;
  hinge.kind = JointKind::kHinge;
  hinge.body_a = AddSphere(world, 0.05, Vec3(1, 0, 1), 0.0, 0.5);
  hinge.anchor = Vec3(1, 0, 2);
  hinge.axis = Vec3::UnitY();
  hinge.damping = 0.05;
  hinge.friction = 0.01;
  ASSERT_TRUE(world.AddJoint(hinge, &id).ok());
  auto method = Method("impulse");
  RunSteps(world, *method, 20);
  proto::Snapshot saved;
  SaveSnapshot(world, *method, &saved);
  World restored;
  std::shared_ptr<ContactMethod> restored_method;
  const Status st = LoadSnapshot(saved, &restored, &restored_method);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(restored.joints().size(), 2u);
  const Joint& j = restored.joints()[0];
  EXPECT_EQ(j.kind, JointKind::kPrismatic);
  EXPECT_TRUE(j.limited);
  EXPECT_EQ(j.lower, -0.2);
  EXPECT_EQ(j.upper, 0.3);
  EXPECT_EQ(j.damping, 0.7);
  EXPECT_EQ(j.friction, 0.4);
  EXPECT_EQ(restored.joints()[1].damping, 0.05);
  EXPECT_EQ(restored.joints()[1].friction, 0.01);
  EXPECT_EQ(HashWorldState(restored), HashWorldState(world));
  EXPECT_EQ(RunSteps(restored, *restored_method, 40), RunSteps(world, *method, 40));
}

// Verifies that the sleep fields enter the state hash only with sleep on,
// so that every hash pinned before sleeping existed still holds.
TEST(SnapshotTest, SleepFieldsAreHashedOnlyWithSleepOn) {
  World world = MixedWorld();
  const uint64_t before = HashWorldState(world);
  world.bodies()[1].rest_time = 0.25;
  EXPECT_EQ(HashWorldState(world), before);
  world.sleep.enabled = true;
  EXPECT_NE(HashWorldState(world), before);
}

// Verifies that the caches a method saves (penalty friction anchors,
// impulse warm starts) are state an exact continuation needs: restoring
// without them changes the trajectory, so the test above would catch a
// snapshot that dropped them.
TEST(SnapshotTest, MethodCachesAreNeededForAnExactContinuation) {
  for (const std::string& name : ContactMethodNames()) {
    SCOPED_TRACE(name);
    World world = MixedWorld();
    auto method = Method(name);
    RunSteps(world, *method, 60);
    if (method->SaveState().empty()) continue;  // a method without caches
    proto::Snapshot saved;
    SaveSnapshot(world, *method, &saved);
    const std::vector<uint64_t> original = RunSteps(world, *method, 40);

    saved.clear_method_state();
    World restored;
    std::shared_ptr<ContactMethod> without;
    ASSERT_TRUE(LoadSnapshot(saved, &restored, &without).ok());
    EXPECT_NE(RunSteps(restored, *without, 40), original);
  }
}

// Verifies that a damaged snapshot is refused with a message naming the
// field, and the target world is left as it was.
TEST(SnapshotTest, DamagedSnapshotsAreRefusedAndLeaveTheWorldUntouched) {
  World world = MixedWorld();
  auto method = Method("impulse");
  proto::Snapshot good;
  SaveSnapshot(world, *method, &good);
  World target;
  AddSphere(target, 0.2, Vec3(0, 0, 1), 0.5);
  const uint64_t before = HashWorldState(target);
  std::shared_ptr<ContactMethod> out;

  proto::Snapshot moved = good;
  moved.mutable_bodies(1)->set_x(2, 5.0);
  Status st = LoadSnapshot(moved, &target, &out);
  EXPECT_NE(st.message().find("state hash"), std::string::npos) << st.message();

  proto::Snapshot short_q = good;
  short_q.mutable_bodies(1)->mutable_q()->RemoveLast();
  st = LoadSnapshot(short_q, &target, &out);
  EXPECT_NE(st.message().find("body 2 q must hold 4 numbers, got 3"), std::string::npos) << st.message();

  proto::Snapshot bad_method = good;
  bad_method.set_contact_method("nosuch");
  st = LoadSnapshot(bad_method, &target, &out);
  EXPECT_NE(st.message().find("nosuch"), std::string::npos) << st.message();

  proto::Snapshot bad_state = good;
  bad_state.set_contact_method("penalty");
  bad_state.clear_method_params();
  bad_state.set_method_state("xyz");
  st = LoadSnapshot(bad_state, &target, &out);
  EXPECT_NE(st.message().find("friction anchors"), std::string::npos) << st.message();
  bad_state.set_contact_method("xpbd");
  st = LoadSnapshot(bad_state, &target, &out);
  EXPECT_NE(st.message().find("friction slips"), std::string::npos) << st.message();

  EXPECT_EQ(HashWorldState(target), before);
  EXPECT_EQ(out, nullptr);
}

// Verifies that a snapshot file reads back equal to what was written.
TEST(SnapshotTest, FilesRoundTrip) {
  World world = MixedWorld();
  auto method = Method("penalty");
  RunSteps(world, *method, 30);
  proto::Snapshot saved, read;
  SaveSnapshot(world, *method, &saved);
  const std::string path = "/tmp/contactsim-snapshot-test-" + std::to_string(::getpid()) + ".pb";
  ASSERT_TRUE(WriteSnapshotFile(path, saved, true).ok());
  ASSERT_TRUE(ReadSnapshotFile(path, &read).ok());
  ::unlink(path.c_str());
  EXPECT_EQ(read.SerializeAsString(), saved.SerializeAsString());
  EXPECT_EQ(ReadSnapshotFile(path, &read).code(), StatusCode::kNotFound);
}

// Verifies that a snapshot keeps every body's collision filter and a
// joint's collide_connected, that a world of default filters writes the
// bytes it wrote before filters existed (no filter fields), and that the
// restored world excludes the same joint pairs.
TEST(SnapshotTest, FiltersAndCollideConnectedRoundTrip) {
  World world = MixedWorld();
  auto method = Method("impulse");
  proto::Snapshot plain;
  SaveSnapshot(world, *method, &plain);
  for (const proto::SnapshotBody& b : plain.bodies()) {
    EXPECT_FALSE(b.has_collision_category() || b.has_collision_mask() || b.has_collision_group());
  }
  for (const proto::SnapshotJoint& j : plain.joints()) EXPECT_FALSE(j.has_collide_connected());
  ASSERT_TRUE(world.SetCollisionFilter(2, 2u, 0xFFFFFFF0u, -5).ok());
  ASSERT_TRUE(world.SetCollisionFilter(3, 0u, 0u, 7).ok());
  JointSettings weld;
  weld.kind = JointKind::kFixed;
  weld.body_a = 3;
  weld.body_b = 4;
  weld.anchor = Vec3(0.5, 0, 0.2);
  weld.collide_connected = true;
  JointSettings ball = weld;
  ball.kind = JointKind::kBall;
  ball.body_a = 2;
  ball.collide_connected = false;
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(weld, &id).ok());
  ASSERT_TRUE(world.AddJoint(ball, &id).ok());
  proto::Snapshot saved;
  SaveSnapshot(world, *method, &saved);
  World restored;
  std::shared_ptr<ContactMethod> m;
  ASSERT_TRUE(LoadSnapshot(saved, &restored, &m).ok());
  ASSERT_EQ(restored.bodies().size(), world.bodies().size());
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const RigidBody& a = world.bodies()[i];
    const RigidBody& b = restored.bodies()[i];
    EXPECT_EQ(a.collision_category, b.collision_category) << i;
    EXPECT_EQ(a.collision_mask, b.collision_mask) << i;
    EXPECT_EQ(a.collision_group, b.collision_group) << i;
  }
  ASSERT_EQ(restored.joints().size(), world.joints().size());
  for (size_t i = 0; i < world.joints().size(); ++i) {
    EXPECT_EQ(restored.joints()[i].collide_connected, world.joints()[i].collide_connected) << i;
  }
  EXPECT_FALSE(restored.joined_pairs().Contains(3, 4));
  EXPECT_TRUE(restored.joined_pairs().Contains(2, 4));
  EXPECT_EQ(HashWorldState(restored), HashWorldState(world));
}

}  // namespace
}  // namespace contactsim
