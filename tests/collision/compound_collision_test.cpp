// Tests of compound bodies in the collision pipeline (narrowphase.cpp's
// DispatchCompound, compound_children.h, aabb.cpp, motion_bound.cpp): a
// compound collides as its children, each child as the plain body it would
// be at its world pose.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/compound_children.h"
#include "service/collision/motion_bound.h"
#include "service/collision/narrowphase.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Capsule;
using testing_util::Convex;
using testing_util::Ground;
using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::RandomVector;
using testing_util::RockHull;
using testing_util::Sphere;

using testing_util::kTol;
constexpr double kMargin = 0.02;  // m, speculative margin of the calls

// A compound of a box, a sphere, a capsule and a hull, spread about the origin.
Shape Mixed() {
  return Shape::Compound({{Shape::Box(Vec3(0.2, 0.05, 0.05)), Vec3(0, 0, 0), Quat::Identity()},
                          {Shape::Sphere(0.08), Vec3(0.25, 0, 0.05), Quat::Identity()},
                          {Shape::Capsule(0.04, 0.1), Vec3(-0.25, 0, 0), Quat(Eigen::AngleAxisd(1.0, Vec3::UnitX()))},
                          {Shape::Convex(RockHull()), Vec3(0, 0.3, 0), Quat(Eigen::AngleAxisd(0.5, Vec3::UnitY()))}});
}

// The contacts of each child pair collided as plain bodies, in child order.
ContactSet ChildByChild(const RigidBody& a, const RigidBody& b) {
  ContactSet out;
  for (int i = 0; i < PieceCount(a); ++i) {
    for (int j = 0; j < PieceCount(b); ++j) Collide(PieceBody(a, i), 0, PieceBody(b, j), 1, kMargin, &out);
  }
  return out;
}

// Verifies that a compound's contacts are its children's, as plain bodies
// posed at body pose times child pose would give, against a plane, every
// primitive and another compound, at random poses: the same points, normals
// and depths, on the parent bodies, with a distinct feature id per point of
// different child pairs.
TEST(CompoundCollision, ContactsAreTheChildrensAtRandomPoses) {
  std::mt19937_64 rng(41);
  const std::vector<Shape> others = {Shape::Plane(Vec3::UnitZ(), 0.0), Shape::Sphere(0.2),
                                     Shape::Box(Vec3(0.2, 0.3, 0.1)),   Shape::Capsule(0.1, 0.2),
                                     Shape::Convex(RockHull()),         Mixed()};
  int touching = 0;
  for (const Shape& other : others) {
    for (int trial = 0; trial < 200; ++trial) {
      const RigidBody a = MakeBody(1, Mixed(), RandomVector(rng, 0.3), RandomRotation(rng));
      const RigidBody b = other.IsPlane() ? Ground(2) : MakeBody(2, other, RandomVector(rng, 0.3), RandomRotation(rng));
      ContactSet got;
      Collide(a, 0, b, 1, kMargin, &got);
      const ContactSet want = ChildByChild(a, b);
      ASSERT_EQ(got.size(), want.size());
      std::set<uint32_t> ids;
      for (size_t k = 0; k < got.size(); ++k) {
        EXPECT_TRUE(got[k].point.isApprox(want[k].point, kTol) || (got[k].point - want[k].point).norm() < kTol);
        EXPECT_TRUE(got[k].normal.isApprox(want[k].normal, kTol));
        EXPECT_NEAR(got[k].depth, want[k].depth, kTol);
        EXPECT_EQ(got[k].id_a, 1);
        EXPECT_EQ(got[k].id_b, 2);
        ids.insert(got[k].feature_id);
      }
      EXPECT_EQ(ids.size(), got.size());
      touching += !got.empty();
    }
  }
  EXPECT_GT(touching, 300);  // most poses overlap: the check is not vacuous
}

// Verifies the narrowphase's symmetry for compounds: swapping the bodies
// gives the same points and feature ids with flipped normals.
TEST(CompoundCollision, SwappingBodiesFlipsNormalsOnly) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const RigidBody a = MakeBody(1, Mixed(), RandomVector(rng, 0.3), RandomRotation(rng));
    const RigidBody b = trial % 2 ? MakeBody(2, Mixed(), RandomVector(rng, 0.3), RandomRotation(rng))
                                  : Box(2, Vec3(0.2, 0.1, 0.3), RandomVector(rng, 0.3), RandomRotation(rng));
    ContactSet ab, ba;
    Collide(a, 0, b, 1, kMargin, &ab);
    Collide(b, 1, a, 0, kMargin, &ba);
    ASSERT_EQ(ab.size(), ba.size());
    for (size_t k = 0; k < ab.size(); ++k) {
      EXPECT_EQ(ab[k].point, ba[k].point);
      EXPECT_EQ(ab[k].normal, Vec3(-ba[k].normal));
      EXPECT_EQ(ab[k].feature_id, ba[k].feature_id);
    }
  }
}

// Verifies an L of two boxes resting on the ground: 8 contacts, 4 under
// each leg, normals up, on the parent body.
TEST(CompoundCollision, LShapeOnGroundTouchesWithBothLegs) {
  const Shape l = Shape::Compound({{Shape::Box(Vec3(0.3, 0.05, 0.05)), Vec3(0, 0, 0), Quat::Identity()},
                                   {Shape::Box(Vec3(0.05, 0.3, 0.05)), Vec3(0.25, 0.35, 0), Quat::Identity()}});
  const RigidBody a = MakeBody(1, l, Vec3(0, 0, 0.049));
  ContactSet got;
  Collide(a, 0, Ground(2), 1, kMargin, &got);
  ASSERT_EQ(got.size(), 8u);
  for (const Contact& c : got) {
    EXPECT_NEAR(c.depth, 0.001, 1e-12);
    EXPECT_TRUE(c.normal.isApprox(Vec3(0, 0, -1), kTol));  // from the L to the ground
  }
}

// Verifies the bounding box is the union of the children's, swept by the
// body's velocity, and the bounding radius holds every child.
TEST(CompoundCollision, AabbAndBoundingRadiusHoldEveryChild) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const RigidBody a = MakeBody(1, Mixed(), RandomVector(rng, 1.0), RandomRotation(rng));
    const Aabb box = ComputeAabb(a, 0.0, 0.0);
    Aabb want{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
    double reach = 0.0;
    for (int k = 0; k < PieceCount(a); ++k) {
      const RigidBody child = PieceBody(a, k);
      const Aabb c = ComputeAabb(child, 0.0, 0.0);
      want.min = want.min.cwiseMin(c.min);
      want.max = want.max.cwiseMax(c.max);
      reach = std::max(reach, (child.x - a.x).norm() + BoundingRadius(child.shape));
    }
    EXPECT_TRUE(box.min.isApprox(want.min, kTol));
    EXPECT_TRUE(box.max.isApprox(want.max, kTol));
    EXPECT_NEAR(BoundingRadius(a.shape), reach, kTol);
  }
}

// Verifies the signed distance of a compound pair (time of impact) is the
// smallest over its child pairs: a dumbbell over the ground is as far as
// its lower ball.
TEST(CompoundCollision, SignedDistanceIsTheNearestChilds) {
  const Shape dumbbell = Shape::Compound({{Shape::Sphere(0.1), Vec3(0, 0, -0.3), Quat::Identity()},
                                          {Shape::Capsule(0.03, 0.2), Vec3::Zero(), Quat::Identity()},
                                          {Shape::Sphere(0.1), Vec3(0, 0, 0.3), Quat::Identity()}});
  const RigidBody a = MakeBody(1, dumbbell, Vec3(0, 0, 0.41));
  EXPECT_NEAR(PairSignedDistance(a, Ground(2), 0.05), 0.01, 1e-12);
  EXPECT_NEAR(PairSignedDistance(a, Ground(2), 0.005), 0.005, 1e-12);  // beyond the margin
}

}  // namespace
}  // namespace contactsim
