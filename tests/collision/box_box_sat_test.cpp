// The closed-form box-box separating-axis test against the general
// polyhedron test on the posed boxes (box_box_sat.h promises the same
// result up to round-off).
#include "service/collision/box_box_sat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::RandomRotation;
using testing_util::RandomVector;

using testing_util::kTol;

void ExpectSameResult(const RigidBody& a, const RigidBody& b, double early_out, const char* what, int trial) {
  PosedPolyhedron pa, pb;
  ASSERT_TRUE(PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb));
  const SatResult general = FindSeparatingAxis(pa, pb, early_out);
  const SatResult boxes = FindBoxBoxSeparatingAxis(a, b, early_out);
  EXPECT_EQ(boxes.axis, general.axis) << what << " trial " << trial << " kinds " << int(boxes.axis.kind) << " "
                                      << int(general.axis.kind);
  EXPECT_NEAR(boxes.separation, general.separation, kTol) << what << " trial " << trial;
  EXPECT_NEAR((boxes.normal - general.normal).norm(), 0.0, 1e-9) << what << " trial " << trial;
  EXPECT_NEAR(boxes.max_separation, general.max_separation, kTol) << what << " trial " << trial;
}

// Separation of the posed boxes along the unit axis n (from A to B): the
// gap between A's support along n and B's along -n.
double GapAlong(const PosedPolyhedron& pa, const PosedPolyhedron& pb, const Vec3& n) {
  double max_a = -std::numeric_limits<double>::infinity(), min_b = std::numeric_limits<double>::infinity();
  for (const Vec3& v : pa.vertices) max_a = std::max(max_a, n.dot(v));
  for (const Vec3& v : pb.vertices) min_b = std::min(min_b, n.dot(v));
  return min_b - max_a;
}

// With an early out each test stops at the first axis that separates by
// more than `early_out`, and the two visit the edge pairs in other orders:
// both must stop or both go on, and where they stop, the axis must really
// separate the boxes by the separation reported.
void ExpectSameEarlyOut(const RigidBody& a, const RigidBody& b, double early_out, const char* what, int trial) {
  PosedPolyhedron pa, pb;
  ASSERT_TRUE(PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb));
  const SatResult general = FindSeparatingAxis(pa, pb, early_out);
  const SatResult boxes = FindBoxBoxSeparatingAxis(a, b, early_out);
  ASSERT_EQ(boxes.separation > early_out, general.separation > early_out) << what << " trial " << trial;
  if (general.separation <= early_out) {
    ExpectSameResult(a, b, early_out, what, trial);
    return;
  }
  EXPECT_NEAR(boxes.normal.norm(), 1.0, 1e-12) << what << " trial " << trial;
  EXPECT_NEAR(GapAlong(pa, pb, boxes.normal), boxes.separation, kTol) << what << " trial " << trial;
  EXPECT_EQ(boxes.max_separation, boxes.separation) << what << " trial " << trial;
}

// A box of random half extents 0.05-0.6 m, centre within +-half_width and
// random orientation, drawn one value per statement (argument order is
// unspecified in C++, and each compiler would test other boxes).
RigidBody RandomBox(BodyId id, double half_width, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.05, 0.6);
  const Vec3 h{size(rng), size(rng), size(rng)};
  const Vec3 x = RandomVector(rng, half_width);
  const Quat q = RandomRotation(rng);
  return Box(id, h, x, q);
}

// Verifies the same axis (kind and face or edge indices), separation,
// normal and unbiased maximum as FindSeparatingAxis on 2,000 random pairs
// of boxes of random sizes, overlapping, touching and apart, without an
// early out; and, with an early out, the same verdict with a true
// separating axis.
TEST(BoxBoxSat, MatchesTheGeneralTestOnRandomPairs) {
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 2000; ++trial) {
    const RigidBody a = RandomBox(1, 0.3, rng);
    const RigidBody b = RandomBox(2, 1.2, rng);
    ExpectSameResult(a, b, std::numeric_limits<double>::infinity(), "no early out", trial);
    ExpectSameEarlyOut(a, b, 0.01, "early out", trial);
  }
}

// Verifies the same choice for the resting pairs of a stack: unit boxes
// side by side and on top of each other, exactly aligned (where the
// general test keeps no edge pair) and turned by up to 1e-3 rad about
// random axes, with gaps and overlaps of up to 1 mm.
TEST(BoxBoxSat, MatchesTheGeneralTestOnNearlyAlignedStacks) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> tilt(-1e-3, 1e-3), gap(-1e-3, 1e-3);
  const Vec3 h(0.5, 0.5, 0.5);
  for (int trial = 0; trial < 600; ++trial) {
    const bool aligned = trial % 3 == 0;
    auto turn = [&]() {
      return aligned ? Quat::Identity() : Quat(Eigen::AngleAxisd(tilt(rng), RandomVector(rng, 1.0).normalized()));
    };
    const Vec3 offset = trial % 2 == 0 ? Vec3{0.5 + tilt(rng) * 100, 0.0, 1.0 + gap(rng)}  // on top, half over
                                       : Vec3(1.0 + gap(rng), 0, 0);                      // side by side
    const RigidBody a = Box(1, h, Vec3::Zero(), turn());
    const RigidBody b = Box(2, h, offset, turn());
    ExpectSameResult(a, b, std::numeric_limits<double>::infinity(), "stack", trial);
    ExpectSameEarlyOut(a, b, 1e-3, "stack, early out", trial);
  }
}

// The contact variant must choose what the full test chooses, bit for bit:
// the same axis, normal and separation (its maximum may cover the faces
// only), and the same verdict against the early out.
void ExpectSameContactAxis(const RigidBody& a, const RigidBody& b, double early_out, const char* what, int trial) {
  const BoxPose pa(a), pb(b);
  const SatResult full = FindBoxBoxSeparatingAxis(pa, pb, early_out);
  const SatResult contact = FindBoxBoxContactAxis(pa, pb, early_out);
  EXPECT_EQ(contact.axis, full.axis) << what << " trial " << trial;
  EXPECT_EQ(contact.separation, full.separation) << what << " trial " << trial;
  EXPECT_EQ(contact.normal, full.normal) << what << " trial " << trial;
}

// Verifies the contact variant against the full test on random pairs of
// random sizes (edge and face contacts, apart and overlapping) and on the
// resting pairs of stacks, with and without an early out.
TEST(BoxBoxSat, ContactAxisIsTheFullTestsChoice) {
  std::mt19937_64 rng(19);
  for (int trial = 0; trial < 3000; ++trial) {
    const RigidBody a = RandomBox(1, 0.3, rng);
    const RigidBody b = RandomBox(2, 1.2, rng);
    ExpectSameContactAxis(a, b, std::numeric_limits<double>::infinity(), "random", trial);
    ExpectSameContactAxis(a, b, 0.01, "random, early out", trial);
  }
  std::uniform_real_distribution<double> tilt(-1e-3, 1e-3), gap(-1e-3, 1e-3);
  const Vec3 h(0.5, 0.5, 0.5);
  for (int trial = 0; trial < 900; ++trial) {
    auto turn = [&]() {
      return trial % 3 == 0 ? Quat::Identity()
                            : Quat(Eigen::AngleAxisd(tilt(rng), RandomVector(rng, 1.0).normalized()));
    };
    const Vec3 offset = trial % 2 == 0 ? Vec3{0.5 + tilt(rng) * 100, 0.0, 1.0 + gap(rng)} : Vec3(1.0 + gap(rng), 0, 0);
    const RigidBody a = Box(1, h, Vec3::Zero(), turn());
    const RigidBody b = Box(2, h, offset, turn());
    ExpectSameContactAxis(a, b, 0.01, "stack", trial);
    ExpectSameContactAxis(a, b, std::numeric_limits<double>::infinity(), "stack, no early out", trial);
  }
}

}  // namespace
}  // namespace contactsim
