// Tests of the barrier method's pair search and additive CCD against
// analytic distances and a brute-force enumeration of every primitive pair.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/pair_search.h"

namespace contactsim {
namespace {

constexpr double kFraction = 0.1;  // the default ccd_fraction

Vec12 Pose(const Vec3& p, const Mat3& R = Mat3::Identity()) { return AffineFromPose(p, R); }

Vec12 Move(const Vec3& dp) {
  Vec12 dq = Vec12::Zero();
  dq.head<3>() = dp;
  return dq;
}

// A sphere's centre 0.5 mm above the top face (z = 0.5) of a unit box,
// against the first triangle of that face that lies under it.
CcdPair SphereOverBox(const BodyGeometry& sphere, const BodyGeometry& box, double gap, const Vec3& motion) {
  const double r = sphere.radius;
  const Vec3 centre(0.1, 0.1, 0.5 + r + gap);
  CcdPair p;
  p.a = &sphere;
  p.b = &box;
  p.qa = Pose(centre);
  p.qb = Pose(Vec3::Zero());
  p.dqa = Move(motion);
  p.dqb = Vec12::Zero();
  for (int t = 0; t < static_cast<int>(box.triangles.size()); ++t) {
    const PrimitivePair pair{PrimitiveKind::kPointTriangle, 0, t, false};
    const PairDistance d = EvaluatePair(sphere, centre, Mat3::Identity(), box, Vec3::Zero(), Mat3::Identity(), pair);
    if (std::abs(d.d - gap) < 1e-12) {
      p.pair = pair;
      return p;
    }
  }
  ADD_FAILURE() << "no triangle under the sphere";
  return p;
}

// Verifies that a pair sliding parallel to a face (no approach) keeps the
// whole step, where the one-shot bound d / |motion| allowed 4.5% of it.
TEST(BarrierCcd, SlidingPairKeepsTheWholeStep) {
  const BodyGeometry sphere = MakeBodyGeometry(Shape::Sphere(0.05));
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3::Constant(0.5)));
  const CcdPair p = SphereOverBox(sphere, box, 5e-4, Vec3(0.01, 0, 0));
  EXPECT_EQ(AdditiveCcd(p, kFraction, 1.0), 1.0);
}

// Verifies the approach case against the analytic time: the gap 0.5 mm
// closes at 1 mm per unit alpha (while sliding 1 cm), so it reaches
// fraction * 0.5 mm at alpha = (1 - fraction) 0.5; CCD returns a safe alpha
// just below it.
TEST(BarrierCcd, ApproachingPairStopsJustBeforeTheTarget) {
  const BodyGeometry sphere = MakeBodyGeometry(Shape::Sphere(0.05));
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3::Constant(0.5)));
  const CcdPair p = SphereOverBox(sphere, box, 5e-4, Vec3(0.01, 0, -1e-3));
  const double exact = (1.0 - kFraction) * 0.5;
  const double alpha = AdditiveCcd(p, kFraction, 1.0);
  EXPECT_LE(alpha, exact);
  EXPECT_GT(alpha, 0.9 * exact);
}

// Verifies that a point falling onto a static plane gets the exact time
// (the distance is linear in alpha).
TEST(BarrierCcd, PointOnPlaneIsExact) {
  const BodyGeometry sphere = MakeBodyGeometry(Shape::Sphere(0.05));
  const BodyGeometry ground = MakeBodyGeometry(Shape::Plane(Vec3::UnitZ(), 0.0));
  CcdPair p;
  p.a = &ground;
  p.b = &sphere;
  p.qa = Pose(Vec3::Zero());
  p.qb = Pose(Vec3(0, 0, 0.05 + 2e-3));
  p.dqa = Vec12::Zero();
  p.dqb = Move(Vec3(0.3, 0, -4e-3));
  p.pair = {PrimitiveKind::kPointPlane, 0, 0, true};
  EXPECT_NEAR(AdditiveCcd(p, kFraction, 1.0), (1.0 - kFraction) * 2e-3 / 4e-3, 1e-12);
}

// Verifies that the search is conservative: every primitive pair that
// comes within reach at either end of a motion (brute force over all pairs)
// is among its candidates, for rotated boxes around a pile and a sphere.
TEST(BarrierPairSearch, FindsEveryPairWithinReach) {
  const BodyGeometry ground = MakeBodyGeometry(Shape::Plane(Vec3::UnitZ(), 0.0));
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3(0.1, 0.15, 0.1)));
  const BodyGeometry ball = MakeBodyGeometry(Shape::Sphere(0.1));
  std::vector<SearchBody> bodies;
  bodies.push_back({&ground, Pose(Vec3::Zero()), Pose(Vec3::Zero()), false});
  for (int i = 0; i < 12; ++i) {
    const Mat3 R = Eigen::AngleAxisd(0.4 * i, Vec3(1, 2, 3 - i).normalized()).toRotationMatrix();
    const Vec3 p(0.19 * (i % 3), 0.2 * ((i / 3) % 2), 0.1 + 0.18 * (i / 6));
    const Vec3 dp = 0.02 * Vec3(std::sin(i), std::cos(2.0 * i), -1.0);
    bodies.push_back({i % 5 == 4 ? &ball : &box, Pose(p, R), Pose(p + dp, R), i != 7});
  }
  const double reach = 0.02;
  PrimitivePairSearch search;
  std::vector<CandidatePair> found;
  search.Find(bodies, reach, JointPairSet(), &found);
  std::set<std::tuple<int, int, int, int, int, bool>> have;
  for (const CandidatePair& c : found) have.insert({c.a, c.b, static_cast<int>(c.pair.kind), c.pair.ia, c.pair.ib, c.pair.swapped});
  int near = 0;
  std::vector<PrimitivePair> pairs;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(bodies.size()); ++j) {
      if (!bodies[i].movable && !bodies[j].movable) continue;
      EnumeratePrimitivePairs(*bodies[i].geometry, *bodies[j].geometry, &pairs);
      for (const PrimitivePair& p : pairs) {
        double d = 1e9;
        for (bool end : {false, true}) {
          const Vec12& qa = end ? bodies[i].q_end : bodies[i].q;
          const Vec12& qb = end ? bodies[j].q_end : bodies[j].q;
          d = std::min(d, EvaluatePair(*bodies[i].geometry, AffinePosition(qa), AffineMatrix(qa), *bodies[j].geometry,
                                       AffinePosition(qb), AffineMatrix(qb), p).d);
        }
        if (d >= reach) continue;
        ++near;
        EXPECT_TRUE(have.count({i, j, static_cast<int>(p.kind), p.ia, p.ib, p.swapped}))
            << "bodies " << i << ", " << j << " kind " << static_cast<int>(p.kind) << " (" << p.ia << ", " << p.ib
            << ") at " << d << " m";
      }
    }
  }
  EXPECT_GT(near, 20);  // the configuration does have close pairs
  std::printf("pair search: %d pairs within reach, %zu candidates\n", near, found.size());
}

}  // namespace
}  // namespace contactsim
