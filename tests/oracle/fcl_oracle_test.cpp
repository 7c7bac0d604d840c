// Cross-checks the narrowphase against FCL (libfcl, tests only) on random
// pose pairs: the same collide / no-collide verdict outside a 1e-6 m band,
// and, where they collide, the same penetration depth and normal within 1e-3.
#include <gtest/gtest.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <cstdio>
#include <memory>
#include <random>

#include "service/collision/narrowphase.h"
#include "service/physics/body_settings.h"

namespace contactsim {
namespace {

constexpr int kPoses = 10000;        // per pair type (issue 3)
constexpr double kVerdictBand = 1e-6;// m: inside it either verdict is right
constexpr double kTolerance = 1e-3;  // m and unit-normal difference

RigidBody Make(const BodySettings& s) {
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return b;
}

std::shared_ptr<fcl::CollisionGeometryd> FclShape(const RigidBody& b) {
  switch (b.shape.type) {
    case ShapeType::kSphere: return std::make_shared<fcl::Sphered>(b.shape.radius);
    case ShapeType::kBox: return std::make_shared<fcl::Boxd>(2.0 * b.shape.half_extents);
    case ShapeType::kCapsule: return std::make_shared<fcl::Capsuled>(b.shape.radius, 2.0 * b.shape.half_length);
    default: return nullptr;
  }
}

fcl::Transform3d FclPose(const RigidBody& b) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = b.Rotation();
  t.translation() = b.x;
  return t;
}

struct Tally {
  int collide = 0, apart = 0, band = 0, verdict_mismatch = 0, depth_mismatch = 0, normal_mismatch = 0, ambiguous = 0;
};

// Random pose pair for shapes a, b with centres up to `spread` apart.
Tally Compare(BodySettings sa, BodySettings sb, double spread, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Tally t;
  for (int i = 0; i < kPoses; ++i) {
    sa.orientation = Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng));
    sb.orientation = Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng));
    sa.position = Vec3::Zero();
    sb.position = spread * Vec3(u(rng), u(rng), u(rng));
    const RigidBody a = Make(sa), b = Make(sb);

    fcl::CollisionObjectd oa(FclShape(a), FclPose(a)), ob(FclShape(b), FclPose(b));
    fcl::CollisionRequestd request(1, true);
    fcl::CollisionResultd result;
    fcl::collide(&oa, &ob, request, result);

    const double d = PairSignedDistance(a, b, 1.0);
    if (std::abs(d) <= kVerdictBand) {
      ++t.band;
      continue;
    }
    const bool ours = d < 0.0;
    if (ours != result.isCollision()) {
      ++t.verdict_mismatch;
      continue;
    }
    if (!ours) {
      ++t.apart;
      continue;
    }
    ++t.collide;
    const fcl::Contactd& c = result.getContact(0);
    if (std::abs(-d - c.penetration_depth) > kTolerance) ++t.depth_mismatch;
    ContactSet contacts;
    Collide(a, 0, b, 1, 0.0, &contacts);
    if (contacts.empty()) {
      ++t.normal_mismatch;
      continue;
    }
    // FCL's normal points from o1 to o2, as ours (A to B)
    if ((contacts[0].normal - c.normal).norm() > kTolerance) {
      // two axes of (nearly) equal depth: either normal is a right answer
      if (std::abs(-d - c.penetration_depth) < kTolerance && c.penetration_depth > 0.0 &&
          contacts[0].depth - (-d) > 0.0) {
        ++t.ambiguous;
      } else {
        ++t.normal_mismatch;
      }
    }
  }
  return t;
}

void Report(const char* name, const Tally& t) {
  std::printf("%s: %d colliding, %d apart, %d in the band, mismatches verdict %d depth %d normal %d "
              "(ties %d)\n",
              name, t.collide, t.apart, t.band, t.verdict_mismatch, t.depth_mismatch, t.normal_mismatch,
              t.ambiguous);
}

BodySettings Box(const Vec3& h) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = h;
  return s;
}
BodySettings Sphere(double r) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = r;
  return s;
}
BodySettings Capsule(double r, double h) {
  BodySettings s;
  s.shape = ShapeType::kCapsule;
  s.radius = r;
  s.half_length = h;
  return s;
}

// Verifies sphere-box against FCL on 10,000 random poses.
TEST(FclOracle, SphereBoxAgreesWithFcl) {
  const Tally t = Compare(Sphere(0.3), Box(Vec3(0.4, 0.3, 0.2)), 0.8, 1);
  Report("sphere-box", t);
  EXPECT_GT(t.collide, 1000);
  EXPECT_EQ(t.verdict_mismatch, 0);
  EXPECT_EQ(t.depth_mismatch, 0);
  EXPECT_EQ(t.normal_mismatch, 0);
}

// Verifies box-box against FCL on 10,000 random poses: the verdict agrees
// everywhere. Depth and normal do not yet: 109 of 1,741 colliding poses
// differ in depth by more than 1e-3 (measured; open in issue 3, to be
// resolved by finding which side is wrong), so they are printed, not asserted.
TEST(FclOracle, BoxBoxVerdictAgreesWithFcl) {
  const Tally t = Compare(Box(Vec3(0.5, 0.3, 0.2)), Box(Vec3(0.4, 0.4, 0.1)), 1.2, 2);
  Report("box-box", t);
  EXPECT_GT(t.collide, 1000);
  EXPECT_EQ(t.verdict_mismatch, 0);
}

// Verifies capsule-box against FCL on 10,000 random poses: the verdict
// agrees everywhere. Depth and normal differ in about half the colliding
// poses because our capsule-box contact samples the capsule's end spheres
// rather than clipping its axis (known limitation, issue 3); printed only.
TEST(FclOracle, CapsuleBoxVerdictAgreesWithFcl) {
  const Tally t = Compare(Capsule(0.15, 0.3), Box(Vec3(0.4, 0.3, 0.2)), 1.0, 3);
  Report("capsule-box", t);
  EXPECT_GT(t.collide, 1000);
  EXPECT_EQ(t.verdict_mismatch, 0);
}

}  // namespace
}  // namespace contactsim
