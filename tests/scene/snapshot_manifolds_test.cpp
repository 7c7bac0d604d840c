// Tests of the kept manifolds in a snapshot (service/scene/snapshot_manifolds.h):
// with manifold reuse on, a run restored from a snapshot into a fresh world
// and a fresh detector continues bit for bit, for every registered method.
#include "service/scene/snapshot_manifolds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "service/scene/snapshot.h"
#include "tests/contact/test_bodies.h"
#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace snapshot_manifolds_test {  // a unity build shares the test files' anonymous namespaces

using testing::AddBox;
using testing::AddValidBody;

// Touching polyhedron pairs, the ones whose manifolds are kept: a static
// floor slab, a stack of three boxes, a box sliding to rest on it, and a
// hull tipping on a box; restitution 0, which every method accepts.
World PolyhedronWorld() {
  World w;
  BodySettings floor;
  floor.shape = ShapeType::kBox;
  floor.half_extents = Vec3(2.0, 2.0, 0.1);
  floor.position = Vec3(0, 0, -0.1);
  floor.fixed = true;
  floor.friction = 0.6;
  AddValidBody(w, floor);
  for (int k = 0; k < 3; ++k) AddBox(w, 0.1, Vec3(0, 0, 0.1 + 0.2 * k), 0.0, 0.6);
  AddBox(w, 0.1, Vec3(0.6, 0, 0.1), 0.0, 0.6, Vec3(0.5, 0, 0));
  AddBox(w, Vec3(0.2, 0.2, 0.05), Vec3(-0.6, 0.5, 0.05), 0.0, 0.6);
  BodySettings hull;
  hull.shape = ShapeType::kConvex;
  hull.points = {{0.1, 0, 0}, {-0.1, 0, 0}, {0, 0.12, 0}, {0, -0.1, 0}, {0, 0, 0.15}, {0.03, 0.02, -0.1}};
  hull.position = Vec3(-0.6, 0.5, 0.21);
  hull.friction = 0.6;
  AddValidBody(w, hull);
  return w;
}

using testing_util::StepHashes;

proto::Snapshot Save(const World& w, const ContactMethod& m, const CollisionDetector& detector) {
  proto::Snapshot s;
  SaveSnapshot(w, m, &s);
  SaveManifolds(detector.manifolds(), &s);
  return s;
}

// A run of PolyhedronWorld under `name` with manifold reuse on, stepped
// kSnapshotStep steps and saved there.
struct ReuseRun {
  explicit ReuseRun(const std::string& name);
  // the hashes of the next n steps
  std::vector<uint64_t> Continue(int n) { return StepHashes(world, *method, detector, n); }
  World world;
  std::shared_ptr<ContactMethod> method;
  CollisionDetector detector;
  proto::Snapshot saved;
};

constexpr int kSnapshotStep = 60, kMoreSteps = 120;

ReuseRun::ReuseRun(const std::string& name) : world(PolyhedronWorld()), method(testing_util::NewMethod(name)) {
  detector.SetManifoldReuse(true);
  StepHashes(world, *method, detector, kSnapshotStep);
  saved = Save(world, *method, detector);
}

// Verifies, for every registered method with manifold reuse on: a snapshot
// taken at step k while boxes and a hull rest and slide on each other holds
// kept manifolds (when the method asks the detector), and the world, method and manifolds restored into a fresh
// world and a fresh detector reproduce the uninterrupted run's hash at every
// later step, ending with the same snapshot, kept manifolds included.
TEST(SnapshotManifoldsTest, RestoredRunWithReuseMatchesTheOriginalBitForBitForEveryMethod) {
  for (const std::string& name : ContactMethodNames()) {
    SCOPED_TRACE(name);
    ReuseRun run(name);
    const proto::Snapshot& saved = run.saved;
    // a method that finds its own pairs (barrier: pair_search.h) keeps none
    if (run.detector.stats().detections > 0) EXPECT_GT(saved.manifolds_size(), 0);
    const std::vector<uint64_t> original = run.Continue(kMoreSteps);
    const std::string original_end = Save(run.world, *run.method, run.detector).SerializeAsString();

    proto::Snapshot parsed;
    ASSERT_TRUE(parsed.ParseFromString(saved.SerializeAsString()));
    World restored;
    std::shared_ptr<ContactMethod> restored_method;
    std::vector<CachedManifold> manifolds;
    ASSERT_TRUE(LoadSnapshot(parsed, &restored, &restored_method).ok());
    const Status st = ReadManifolds(parsed, &manifolds);
    ASSERT_TRUE(st.ok()) << st.message();
    CollisionDetector fresh;
    fresh.SetManifoldReuse(true);
    fresh.RestoreManifolds(std::move(manifolds));
    const std::vector<uint64_t> again = StepHashes(restored, *restored_method, fresh, kMoreSteps);
    ASSERT_EQ(again.size(), original.size());
    for (size_t i = 0; i < original.size(); ++i) {
      ASSERT_EQ(again[i], original[i]) << "first divergence at step " << kSnapshotStep + 1 + i;
    }
    EXPECT_EQ(Save(restored, *restored_method, fresh).SerializeAsString(), original_end);
  }
}

// Verifies that the kept manifolds are state that changes results: the same
// snapshot restored without them (an older snapshot; reuse starts cold)
// loads, and its run leaves the original's for at least one method (the
// test above would catch a snapshot that dropped them). The separating-axis
// cache, which a restore also starts cold, changes no result.
TEST(SnapshotManifoldsTest, WithoutTheManifoldsReuseStartsColdAndTheRunDiffers) {
  int differing = 0;
  for (const std::string& name : ContactMethodNames()) {
    SCOPED_TRACE(name);
    ReuseRun run(name);
    proto::Snapshot& saved = run.saved;
    const std::vector<uint64_t> original = run.Continue(kMoreSteps);

    saved.clear_manifolds();
    World restored;
    std::shared_ptr<ContactMethod> restored_method;
    std::vector<CachedManifold> manifolds(1);
    ASSERT_TRUE(LoadSnapshot(saved, &restored, &restored_method).ok());
    ASSERT_TRUE(ReadManifolds(saved, &manifolds).ok());
    EXPECT_TRUE(manifolds.empty());
    CollisionDetector cold;
    cold.SetManifoldReuse(true);
    if (StepHashes(restored, *restored_method, cold, kMoreSteps) != original) ++differing;
  }
  EXPECT_GT(differing, 0);
}

// Verifies that damaged manifolds are refused with a message naming the
// pair and the field, leaving the output as it was.
TEST(SnapshotManifoldsTest, DamagedManifoldsAreRefused) {
  const proto::Snapshot good = ReuseRun("impulse").saved;
  ASSERT_GE(good.manifolds_size(), 2);
  const std::vector<CachedManifold> before(1);
  auto refused = [&](const proto::Snapshot& s, const std::string& words) {
    std::vector<CachedManifold> out = before;
    const Status st = ReadManifolds(s, &out);
    EXPECT_FALSE(st.ok());
    EXPECT_NE(st.message().find(words), std::string::npos) << st.message();
    EXPECT_EQ(out.size(), 1u);
  };
  proto::Snapshot s = good;
  s.mutable_manifolds(0)->mutable_points(0)->clear_normal();
  refused(s, "point 0 normal must hold 3 numbers");
  s = good;
  s.mutable_manifolds(1)->set_reach_b(-1.0);
  refused(s, "reach_b must be finite");
  s = good;
  s.mutable_manifolds(0)->clear_points();
  refused(s, "must hold 1 to 4 points");
  s = good;
  s.mutable_manifolds()->SwapElements(0, 1);
  refused(s, "ascending (body_a, body_b) order");
  s = good;
  s.mutable_manifolds(0)->set_p_ab(0, std::nan(""));
  refused(s, "p_ab must be finite");
}

}  // namespace snapshot_manifolds_test
}  // namespace contactsim
