// Tests of the barrier method's primitive distances near d = 0: signed
// point-triangle and crossing edge-edge distances (contact_primitives.h),
// against the analytic distances of unit boxes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "service/contact/barrier/contact_primitives.h"

namespace contactsim {
namespace {

constexpr double kDepth = 2e-5;  // m, the solver's signed depth at the default d_hat

// The smallest distance of a pair kind between two unit cubes, box b at pb
// (rotated by Rb), with the normal of that pair.
PairDistance Smallest(PrimitiveKind kind, const Vec3& pb, const Mat3& Rb = Mat3::Identity()) {
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3::Constant(0.5)));
  std::vector<PrimitivePair> pairs;
  EnumeratePrimitivePairs(box, box, &pairs);
  PairDistance best;
  best.d = std::numeric_limits<double>::infinity();
  for (const PrimitivePair& p : pairs) {
    if (p.kind != kind) continue;
    const PairDistance d = EvaluatePair(box, Vec3::Zero(), Mat3::Identity(), box, pb, Rb, p, kDepth);
    if (d.d < best.d) best = d;
  }
  return best;
}

// Verifies that a box stacked exactly on another (d = 0, no direction
// between the closest points) gets the face normal, pointing from a to b.
TEST(BarrierPrimitives, TouchingFacesGetTheFaceNormal) {
  const PairDistance d = Smallest(PrimitiveKind::kPointTriangle, Vec3(0.3, 0.2, 1.0));
  EXPECT_NEAR(d.d, 0.0, 1e-12);
  EXPECT_NEAR(d.n.z(), 1.0, 1e-12);
}

// Verifies that a box sunk 5 um into another has a signed point-triangle
// distance of -5 um (an unsigned distance would read +5 um, as if apart).
TEST(BarrierPrimitives, PointJustBehindAFaceIsNegative) {
  const PairDistance d = Smallest(PrimitiveKind::kPointTriangle, Vec3(0.3, 0.2, 1.0 - 5e-6));
  EXPECT_NEAR(d.d, -5e-6, 1e-12);
  EXPECT_NEAR(d.n.z(), 1.0, 1e-12);
}

// Verifies that a point deeper than the signed depth is unsigned again
// (seen from a face on the far side it is not inside).
TEST(BarrierPrimitives, PointFarBehindAFaceIsUnsigned) {
  const PairDistance d = Smallest(PrimitiveKind::kPointTriangle, Vec3(0.3, 0.2, 1.0 - 1e-3));
  EXPECT_GE(d.d, 0.0);
}

// Verifies crossing edges: b, turned 45 degrees about x, rests its lowest
// edge (along x, sqrt(1/2) below its centre) across a's top edge along y at
// x = 0.5; the signed distance is the height of one edge above the other,
// negative when they have passed through each other, with the normal +z.
TEST(BarrierPrimitives, CrossingEdgesAreSigned) {
  const Mat3 R = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix();
  const double low = std::sqrt(0.5);
  for (double gap : {3e-6, -3e-6}) {
    const PairDistance d = Smallest(PrimitiveKind::kEdgeEdge, Vec3(0.2, 0.0, 0.5 + low + gap), R);
    EXPECT_NEAR(d.d, gap, 1e-9) << gap;
    EXPECT_NEAR(d.n.z(), 1.0, 1e-9) << gap;
  }
}

}  // namespace
}  // namespace contactsim
