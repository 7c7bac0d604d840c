// ContactDepthBound is never below a contact the narrowphase reports, for
// pairs of boxes, small and large hulls, compounds of them and a hull on
// the ground, in random overlapping poses and along random directions and
// the contacts' own normals; it is unknown (+infinity) for other shapes
// and for a plane off its normal, and tight (the depth plus the separating
// axis test's preference bias) for a box resting on the ground.
#include "service/collision/depth_bound.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/collision/polyhedron_sat.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Convex;
using testing_util::Ground;
using testing_util::Hull;
using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::RandomVector;
using testing_util::RockHull;

constexpr int kTrials = 300;

// `count` points on an ellipsoid of semi-axes `axes` (m), as a link's mesh gives
std::shared_ptr<const ConvexHull> Ellipsoid(std::mt19937_64& rng, int count, const Vec3& axes) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    points.push_back(Vec3{normal(rng), normal(rng), normal(rng)}.normalized().cwiseProduct(axes));
  }
  return Hull(points);
}

// Every contact of the pair, for every direction tried, is no deeper than
// the bound; returns how many contacts were checked.
int CheckPair(const RigidBody& a, const RigidBody& b, std::mt19937_64& rng) {
  ContactSet contacts;
  Collide(a, 0, b, 1, 0.0, &contacts);
  std::vector<Vec3> directions;
  for (const Contact& c : contacts) directions.push_back(c.normal);
  for (int k = 0; k < 4; ++k) directions.push_back(RandomVector(rng, 1.0).normalized());
  for (const Vec3& u : directions) {
    const double bound = ContactDepthBound(a, b, u);
    for (const Contact& c : contacts) EXPECT_LE(c.depth, bound) << "u " << u.transpose();
  }
  return static_cast<int>(contacts.size());
}

// Verifies the bound over boxes, hulls of 12 and of 300 points, and a
// compound of two hulls, each against each, overlapping by up to a few cm.
TEST(ContactDepthBound, IsNeverBelowAContactOfPolyhedraAndCompounds) {
  std::mt19937_64 rng(41);
  const auto large = Ellipsoid(rng, 300, {0.12, 0.08, 0.2});
  std::vector<ShapeChild> children(2);
  children[0].shape = Shape::Convex(RockHull());
  children[0].position = {0.0, 0.0, -0.1};
  children[1].shape = Shape::Convex(large);
  children[1].position = {0.05, 0.0, 0.15};
  children[1].orientation = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitX()));
  const std::vector<Shape> shapes = {Shape::Box({0.1, 0.15, 0.2}), Shape::Convex(RockHull()), Shape::Convex(large),
                                     Shape::Compound(children)};
  int contacts = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    for (size_t i = 0; i < shapes.size(); ++i) {
      for (size_t j = 0; j < shapes.size(); ++j) {
        const RigidBody a = MakeBody(1, shapes[i], Vec3::Zero(), RandomRotation(rng));
        const RigidBody b = MakeBody(2, shapes[j], RandomVector(rng, 0.3), RandomRotation(rng));
        contacts += CheckPair(a, b, rng);
      }
    }
  }
  EXPECT_GT(contacts, kTrials);  // most poses overlap
}

// Verifies the bound for a hull and a box on the ground, along the
// ground's normal (either order), and that it is unknown off the normal.
TEST(ContactDepthBound, HoldsOnTheGroundAlongItsNormalOnly) {
  std::mt19937_64 rng(7);
  const auto large = Ellipsoid(rng, 300, {0.12, 0.08, 0.2});
  const RigidBody ground = Ground(9);
  for (int trial = 0; trial < kTrials; ++trial) {
    std::uniform_real_distribution<double> height(0.0, 0.2);
    const RigidBody hull = Convex(1, large, {0.0, 0.0, height(rng)}, RandomRotation(rng));
    const RigidBody box = Box(2, {0.1, 0.05, 0.2}, {0.0, 0.0, height(rng)}, RandomRotation(rng));
    for (const RigidBody* body : {&hull, &box}) {
      ContactSet contacts;
      Collide(*body, 0, ground, 1, 0.0, &contacts);
      const double down = ContactDepthBound(*body, ground, -Vec3::UnitZ());
      const double up = ContactDepthBound(ground, *body, Vec3::UnitZ());
      for (const Contact& c : contacts) {
        EXPECT_LE(c.depth, down);
        EXPECT_LE(c.depth, up);
      }
    }
  }
  const RigidBody box = Box(2, {0.1, 0.1, 0.1}, {0.0, 0.0, 0.05});
  EXPECT_EQ(ContactDepthBound(box, ground, Vec3(0.6, 0.0, -0.8)), std::numeric_limits<double>::infinity());
}

// Verifies that a sphere (no polyhedron) gives no bound.
TEST(ContactDepthBound, IsUnknownForOtherShapes) {
  const RigidBody sphere = testing_util::Sphere(1, 0.1, Vec3::Zero());
  const RigidBody box = Box(2, {0.1, 0.1, 0.1}, {0.15, 0.0, 0.0});
  EXPECT_EQ(ContactDepthBound(sphere, box, Vec3::UnitX()), std::numeric_limits<double>::infinity());
}

// Verifies that a box resting 2 mm deep in the ground is bounded at its
// depth plus the separating-axis preference bias (polyhedron_sat.h) and
// round-off: the bound the impact search compares with a margin.
TEST(ContactDepthBound, IsTheDepthPlusTheBiasForARestingBox) {
  const double depth = 0.002;  // m
  const RigidBody box = Box(1, {0.1, 0.1, 0.1}, {0.0, 0.0, 0.1 - depth});
  const double bound = ContactDepthBound(box, Ground(2), -Vec3::UnitZ());
  EXPECT_NEAR(bound, depth + kSatMaxBias + kSatAbsTolerance, 2e-9);
}

}  // namespace
}  // namespace contactsim
