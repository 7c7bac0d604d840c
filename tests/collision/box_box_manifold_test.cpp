// The box-box manifold without posing against PolyhedronManifold on the
// posed boxes (box_box_manifold.h promises the same contacts bit for bit,
// which keeps every method's determinism pins).
#include "service/collision/box_box_manifold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "service/collision/box_box_sat.h"
#include "service/collision/polyhedron_manifold.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::RandomRotation;
using testing_util::RandomVector;

// Bit-for-bit equality of two doubles (EXPECT_EQ would take -0.0 for 0.0).
bool SameBits(double x, double y) { return std::memcmp(&x, &y, sizeof(double)) == 0; }
bool SameBits(const Vec3& u, const Vec3& v) {
  return SameBits(u.x(), v.x()) && SameBits(u.y(), v.y()) && SameBits(u.z(), v.z());
}

// Collides the pair both ways and expects the same contacts, bit for bit;
// returns how many points the pair has.
size_t ExpectSameContacts(const RigidBody& a, const RigidBody& b, double margin, const char* what, int trial) {
  const BoxPose box_a(a), box_b(b);
  const SatResult sat = FindBoxBoxSeparatingAxis(box_a, box_b, margin);
  if (sat.separation > margin) return 0;
  PosedPolyhedron pa, pb;
  EXPECT_TRUE(PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb));
  ClipBuffers clip;
  ContactSet posed, boxes;
  PolyhedronManifold(pa, pb, sat, margin, &posed, &clip);
  BoxBoxManifold(box_a, box_b, sat, margin, &boxes);
  EXPECT_EQ(boxes.size(), posed.size()) << what << " trial " << trial;
  for (size_t k = 0; k < std::min(boxes.size(), posed.size()); ++k) {
    EXPECT_TRUE(SameBits(boxes[k].point, posed[k].point)) << what << " trial " << trial << " point " << k;
    EXPECT_TRUE(SameBits(boxes[k].normal, posed[k].normal)) << what << " trial " << trial << " point " << k;
    EXPECT_TRUE(SameBits(boxes[k].depth, posed[k].depth)) << what << " trial " << trial << " point " << k;
    EXPECT_EQ(boxes[k].feature_id, posed[k].feature_id) << what << " trial " << trial << " point " << k;
  }
  return posed.size();
}

// Verifies that each vertex and face plane posed one at a time is the posed
// box's, bit for bit, over random boxes.
TEST(BoxBoxManifold, VerticesAndPlanesArePosePolyhedrons) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> size(0.05, 2.0);
  for (int trial = 0; trial < 500; ++trial) {
    const Vec3 h{size(rng), size(rng), size(rng)};
    const Vec3 x = RandomVector(rng, 5.0);
    const RigidBody body = Box(1, h, x, RandomRotation(rng));
    PosedPolyhedron posed;
    ASSERT_TRUE(PosePolyhedron(body, &posed));
    const BoxPose box(body);
    for (int v = 0; v < 8; ++v) EXPECT_TRUE(SameBits(BoxVertex(box, v), posed.vertices[v])) << trial;
    for (int f = 0; f < 6; ++f) {
      const Vec3 n = BoxFaceNormal(box.R, f);
      EXPECT_TRUE(SameBits(n, posed.normals[f])) << trial;
      EXPECT_TRUE(SameBits(BoxFaceOffset(n, box.x, box.h, f), posed.offsets[f])) << trial;
    }
  }
}

// Verifies the same contacts as the posed boxes' manifold on 3,000 random
// pairs of random sizes and orientations, overlapping shallow and deep
// (face and edge axes, clipped polygons of up to eight points, and the
// deepest-vertex fallback of deep overlaps), with a 1 cm margin.
TEST(BoxBoxManifold, MatchesThePosedManifoldOnRandomPairs) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> size(0.05, 0.6);
  size_t points = 0;
  int touching = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 ha{size(rng), size(rng), size(rng)};
    const Vec3 hb{size(rng), size(rng), size(rng)};
    const RigidBody a = Box(1, ha, RandomVector(rng, 0.3), RandomRotation(rng));
    const RigidBody b = Box(2, hb, RandomVector(rng, 0.9), RandomRotation(rng));
    const size_t n = ExpectSameContacts(a, b, 0.01, "random", trial);
    points += n;
    touching += n > 0 ? 1 : 0;
  }
  // most pairs touch, so the comparison is not empty
  EXPECT_GT(touching, 1000);
  EXPECT_GT(points, 2000u);
}

// Verifies the same contacts for the resting pairs of a stack and a
// pyramid: unit boxes side by side and on top of each other (exactly
// aligned, and turned by up to 1e-3 rad about random axes), flush or half
// over, with gaps and overlaps of up to 1 mm: flush faces whose clip
// planes pass through the other face's corners.
TEST(BoxBoxManifold, MatchesThePosedManifoldOnNearlyAlignedStacks) {
  std::mt19937_64 rng(45);
  std::uniform_real_distribution<double> tilt(-1e-3, 1e-3), gap(-1e-3, 1e-3);
  const Vec3 h(0.5, 0.5, 0.5);
  for (int trial = 0; trial < 900; ++trial) {
    const bool aligned = trial % 3 == 0;
    auto turn = [&]() {
      return aligned ? Quat::Identity() : Quat(Eigen::AngleAxisd(tilt(rng), RandomVector(rng, 1.0).normalized()));
    };
    const int kind = trial % 3;
    const Vec3 offset = kind == 0   ? Vec3{0.5 + tilt(rng) * 100, 0.0, 1.0 + gap(rng)}  // on top, half over
                        : kind == 1 ? Vec3{tilt(rng), 0.0, 1.0 + gap(rng)}              // on top, flush
                                    : Vec3(1.0 + gap(rng), 0, 0);                      // side by side
    const RigidBody a = Box(1, h, Vec3::Zero(), turn());
    const RigidBody b = Box(2, h, offset, turn());
    EXPECT_GT(ExpectSameContacts(a, b, 0.01, "stack", trial), 0u) << trial;
  }
}

}  // namespace
}  // namespace contactsim
