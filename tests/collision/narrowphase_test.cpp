// Properties of the narrowphase over every pair of shape types: the dispatch
// table, swapping the bodies, speculative contacts and continuity.
#include "service/collision/narrowphase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::RandomVector;

// Swapping only reorders the same computation, so results agree to round-off.
constexpr double kSwapTol = 1e-12;  // m
// Random trials per pair type: enough for many contacts of each kind.
constexpr int kNarrowphaseTrials = 300;

// One body of each shape type, about 0.3 m in size; the plane has a random pose too.
RigidBody RandomBody(ShapeType type, BodyId id, std::mt19937_64& rng) {
  static const auto rock = testing_util::RockHull();
  Shape shape;
  switch (type) {
    case ShapeType::kSphere: shape = Shape::Sphere(0.3); break;
    case ShapeType::kBox: shape = Shape::Box(Vec3(0.3, 0.2, 0.25)); break;
    case ShapeType::kCapsule: shape = Shape::Capsule(0.15, 0.3); break;
    case ShapeType::kConvex: shape = Shape::Convex(rock); break;
    default: shape = Shape::Plane(Vec3::UnitZ(), 0.1); break;
  }
  // one draw per statement: argument order is unspecified in C++, and each
  // compiler would test other poses
  const Vec3 x = RandomVector(rng, 0.4);
  const Quat q = RandomRotation(rng);
  return MakeBody(id, shape, x, q);
}

const ShapeType kTypes[] = {ShapeType::kSphere, ShapeType::kBox, ShapeType::kCapsule, ShapeType::kConvex,
                            ShapeType::kPlane};

// Verifies, for every pair of shape types on random poses, that swapping A and B
// gives the same points, depths and feature ids with flipped normals.
TEST(NarrowphaseTest, SwappingBodiesFlipsNormalsAndKeepsPoints) {
  std::mt19937_64 rng(7);
  for (ShapeType ta : kTypes) {
    for (ShapeType tb : kTypes) {
      if (ta == ShapeType::kPlane && tb == ShapeType::kPlane) continue;
      int with_contacts = 0;
      for (int trial = 0; trial < kNarrowphaseTrials; ++trial) {
        // ids equal on odd trials: the order then falls back to the poses
        const BodyId id_b = trial % 2 == 0 ? 2 : 1;
        const RigidBody a = RandomBody(ta, 1, rng);
        const RigidBody b = RandomBody(tb, id_b, rng);
        ContactSet ab, ba;
        Collide(a, 0, b, 1, 0.05, &ab);
        Collide(b, 1, a, 0, 0.05, &ba);
        const std::string pair = std::string(ShapeTypeName(ta)) + "-" + ShapeTypeName(tb);
        ASSERT_EQ(ab.size(), ba.size()) << pair << " trial " << trial;
        with_contacts += !ab.empty();
        for (size_t k = 0; k < ab.size(); ++k) {
          EXPECT_NEAR((ab[k].point - ba[k].point).norm(), 0.0, kSwapTol) << pair;
          EXPECT_NEAR((ab[k].normal + ba[k].normal).norm(), 0.0, kSwapTol) << pair;
          EXPECT_NEAR(ab[k].depth, ba[k].depth, kSwapTol) << pair;
          EXPECT_EQ(ab[k].feature_id, ba[k].feature_id) << pair;
          EXPECT_EQ(ab[k].a, 0);
          EXPECT_EQ(ba[k].a, 1);
          EXPECT_EQ(ab[k].id_b, b.id);
          EXPECT_NEAR(ab[k].normal.norm(), 1.0, kSwapTol) << pair;
        }
      }
      EXPECT_GT(with_contacts, kNarrowphaseTrials / 10) << ShapeTypeName(ta) << "-" << ShapeTypeName(tb);
    }
  }
}

// Verifies that every contact respects the margin and that a larger margin
// only adds contacts (the overlapping ones are found with margin 0 too).
TEST(NarrowphaseTest, MarginOnlyAddsSpeculativeContacts) {
  std::mt19937_64 rng(11);
  for (ShapeType ta : kTypes) {
    for (ShapeType tb : kTypes) {
      if (ta == ShapeType::kPlane && tb == ShapeType::kPlane) continue;
      for (int trial = 0; trial < kNarrowphaseTrials; ++trial) {
        const RigidBody a = RandomBody(ta, 1, rng);
        const RigidBody b = RandomBody(tb, 2, rng);
        ContactSet tight, wide;
        Collide(a, 0, b, 1, 0.0, &tight);
        Collide(a, 0, b, 1, 0.1, &wide);
        for (const Contact& c : tight) EXPECT_GT(c.depth, 0.0);
        for (const Contact& c : wide) EXPECT_GT(c.depth, -0.1);
        if (!tight.empty()) {
          EXPECT_FALSE(wide.empty());
        }
      }
    }
  }
}

// Verifies that the pair's signed distance is continuous along a straight
// approach: consecutive samples differ by at most the step (it is 1-Lipschitz
// in a translation) plus round-off, from well apart to overlapping.
TEST(NarrowphaseTest, SignedDistanceIsContinuousAlongAnApproach) {
  constexpr double kStep = 1e-3;           // m per sample
  constexpr double kLipschitzTol = 1e-9;   // m, round-off and the capsule's search tolerance
  constexpr double kMargin = 0.2;          // m
  std::mt19937_64 rng(13);
  for (ShapeType ta : kTypes) {
    for (ShapeType tb : kTypes) {
      if (ta == ShapeType::kPlane && tb == ShapeType::kPlane) continue;
      for (int path = 0; path < 5; ++path) {
        const RigidBody a = RandomBody(ta, 1, rng);
        RigidBody b = RandomBody(tb, 2, rng);
        const Vec3 start = a.x + 1.2 * RandomVector(rng, 1.0).normalized();
        const Vec3 dir = (a.x - start).normalized();
        double previous = std::numeric_limits<double>::quiet_NaN();
        bool touched = false;
        for (int k = 0; k <= 1200; ++k) {
          b.x = start + k * kStep * dir;
          const double d = PairSignedDistance(a, b, kMargin);
          EXPECT_LE(d, kMargin);
          if (k > 0) {
            EXPECT_LE(std::abs(d - previous), kStep + kLipschitzTol)
                << ShapeTypeName(ta) << "-" << ShapeTypeName(tb) << " sample " << k;
          }
          touched = touched || d < 0.0;
          previous = d;
        }
        EXPECT_TRUE(touched) << ShapeTypeName(ta) << "-" << ShapeTypeName(tb);
      }
    }
  }
}

// Verifies that two planes never collide and that non-finite poses give no contacts.
TEST(NarrowphaseTest, PlanePairsAndNonFinitePosesGiveNoContacts) {
  ContactSet out;
  const RigidBody ground = testing_util::Ground(1);
  EXPECT_EQ(Collide(ground, 0, testing_util::Ground(2), 1, 1.0, &out), 0);
  RigidBody bad = testing_util::Sphere(3, 0.5, Vec3(0, 0, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(Collide(bad, 0, ground, 1, 1.0, &out), 0);
  EXPECT_TRUE(out.empty());
}

// Verifies that Collide appends to the set and returns the number it added.
TEST(NarrowphaseTest, CollideAppendsAndReturnsTheCount) {
  ContactSet out(2);
  const int n = Collide(testing_util::Box(1, Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0.49)), 4,
                        testing_util::Ground(2), 7, 0.0, &out);
  EXPECT_EQ(n, 4);
  EXPECT_EQ(out.size(), 6u);
  EXPECT_EQ(out[5].a, 4);
  EXPECT_EQ(out[5].b, 7);
}

}  // namespace
}  // namespace contactsim
