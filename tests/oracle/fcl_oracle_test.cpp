// Cross-checks the narrowphase against FCL (libfcl, tests only) on 10,000
// random pose pairs per pair type: the same collide / no-collide
// verdict outside a 1e-6 m band, and, where they collide, the same
// penetration depth and normal within 1e-3.
//
// The verdict is FCL's collide() with its defaults. The depth and normal are
// FCL's exact signed distance instead (libccd GJK, and EPA when overlapping,
// on the shapes as fcl::Convex polytopes), because collide()'s own depths are
// not the minimum penetration depth:
// - box-box runs ODE's dBoxBox (boxBox2), which like ours prefers face axes
//   over edge axes by a factor 1.05 but, unlike ours, without a cap: its
//   depth is up to 2.5 cm deeper than the true one here (109 of 1,741
//   colliding poses off by more than 1e-3). The true minimum over the 15
//   axes, computed independently, equals ours to 8e-16 and the EPA depth to
//   1e-15 in every pose.
// - capsule-box and convex-convex run libccd's MPR, which finds a
//   penetration along a portal towards the centres, not the minimum.
// The printed line counts collide()'s depths that differ from the exact one.
//
// Round shapes go in as their core (a sphere's centre, a capsule's segment:
// an fcl::Capsule of radius 0) and the radius is added: a sphere or capsule
// is its core grown by r in every direction, so its penetration depth with a
// polytope is r - sd(core, polytope) exactly, and EPA stays on polytopes,
// where it converges (on curved shapes libccd's EPA stops at its tolerance,
// ~1e-3 in the normal, and asserts below ~3e-8).
//
// Ours are checked twice: the unbiased answer (PairSignedDistance, whose
// normal is the minimum-penetration axis) and the manifold Collide() returns
// (its deepest point; its normal may prefer a face whose depth is within
// kSatMaxBias + kSatAbsTolerance of the minimum, polyhedron_sat.h, which is
// counted apart when the overlap along it, computed here from the vertices,
// confirms it).
#include <gtest/gtest.h>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>

#include "service/collision/narrowphase.h"
#include "service/collision/polyhedron_sat.h"
#include "service/physics/body_settings.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

constexpr int kPoses = 10000;         // per pair type
constexpr double kVerdictBand = 1e-6; // m: inside it either verdict is right
constexpr double kTolerance = 1e-3;   // m, and unit-normal difference
// Two axes whose overlaps agree to this (m) are both a minimum-penetration
// direction (EPA is exact to ~1e-15 m on these polytopes).
constexpr double kTieTolerance = 1e-9;
// Below this core distance (m) the witness points of the reference coincide
// and give no normal: the core touches, the normal is undefined there.
constexpr double kWitnessLength = 1e-9;

RigidBody Make(const BodySettings& s) {
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return b;
}

fcl::Transform3d FclPose(const RigidBody& b) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = b.Rotation();
  t.translation() = b.x;
  return t;
}

std::shared_ptr<fcl::Convexd> FclConvex(const std::vector<Vec3>& vertices,
                                        const std::vector<std::vector<int>>& loops) {
  auto v = std::make_shared<std::vector<fcl::Vector3d>>(vertices.begin(), vertices.end());
  auto f = std::make_shared<std::vector<int>>();
  for (const auto& loop : loops) {
    f->push_back(static_cast<int>(loop.size()));
    f->insert(f->end(), loop.begin(), loop.end());
  }
  return std::make_shared<fcl::Convexd>(v, static_cast<int>(loops.size()), f);
}

std::vector<Vec3> BoxVertices(const Vec3& h) {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return v;
}

// FCL's own shape, for collide()'s verdict.
std::shared_ptr<fcl::CollisionGeometryd> FclShape(const RigidBody& b) {
  switch (b.shape.type) {
    case ShapeType::kSphere: return std::make_shared<fcl::Sphered>(b.shape.radius);
    case ShapeType::kBox: return std::make_shared<fcl::Boxd>(2.0 * b.shape.half_extents);
    case ShapeType::kCapsule: return std::make_shared<fcl::Capsuled>(b.shape.radius, 2.0 * b.shape.half_length);
    case ShapeType::kConvex: {
      std::vector<std::vector<int>> loops;
      for (const auto& face : b.shape.hull->faces) loops.push_back(face.vertices);
      return FclConvex(b.shape.hull->vertices, loops);
    }
    default: return nullptr;
  }
}

// The polytope core of a shape for the signed distance, and the radius grown
// around it.
std::shared_ptr<fcl::ShapeBased> FclCore(const RigidBody& b, double* radius) {
  *radius = 0.0;
  switch (b.shape.type) {
    case ShapeType::kSphere:
      *radius = b.shape.radius;
      return std::make_shared<fcl::Sphered>(0.0);
    case ShapeType::kCapsule:
      *radius = b.shape.radius;
      return std::make_shared<fcl::Capsuled>(0.0, 2.0 * b.shape.half_length);
    case ShapeType::kBox: {
      const int loops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
      std::vector<std::vector<int>> faces;
      for (const auto& l : loops) faces.emplace_back(l, l + 4);
      return FclConvex(BoxVertices(b.shape.half_extents), faces);
    }
    case ShapeType::kConvex: return std::static_pointer_cast<fcl::ShapeBased>(FclShape(b));
    default: return nullptr;
  }
}

struct Reference {
  double depth = 0.0;          // m, exact minimum penetration depth
  Vec3 normal = Vec3::Zero();  // unit, from A to B; zero when undefined
};

template <typename CoreA, typename CoreB>
Reference SignedDistance(const CoreA& ca, const RigidBody& a, double ra, const CoreB& cb, const RigidBody& b,
                         double rb) {
  fcl::detail::GJKSolver_libccd<double> solver;
  double sd;
  fcl::Vector3d pa, pb;
  solver.shapeSignedDistance(ca, FclPose(a), cb, FclPose(b), &sd, &pa, &pb);
  Reference r;
  r.depth = ra + rb - sd;
  // apart: from A's witness to B's; overlapping: B's deepest point is A's + depth
  const Vec3 w = sd >= 0.0 ? Vec3(pb - pa) : Vec3(pa - pb);
  if (w.norm() > kWitnessLength) r.normal = w.normalized();
  return r;
}

// Dispatches on the two core types (fcl's solver is templated on them).
Reference ExactReference(const RigidBody& a, const RigidBody& b) {
  double ra, rb;
  const auto ca = FclCore(a, &ra), cb = FclCore(b, &rb);
  const auto with_b = [&](const auto& core_a) {
    if (auto* s = dynamic_cast<const fcl::Sphered*>(cb.get())) return SignedDistance(core_a, a, ra, *s, b, rb);
    if (auto* c = dynamic_cast<const fcl::Capsuled*>(cb.get())) return SignedDistance(core_a, a, ra, *c, b, rb);
    return SignedDistance(core_a, a, ra, *static_cast<const fcl::Convexd*>(cb.get()), b, rb);
  };
  if (auto* s = dynamic_cast<const fcl::Sphered*>(ca.get())) return with_b(*s);
  if (auto* c = dynamic_cast<const fcl::Capsuled*>(ca.get())) return with_b(*c);
  return with_b(*static_cast<const fcl::Convexd*>(ca.get()));
}

// Support value max_{p in body} dir . p, from the body's own vertices (or
// core and radius), independently of the narrowphase.
double Support(const RigidBody& b, const Vec3& dir) {
  const Mat3 R = b.Rotation();
  double best = -1e300;
  switch (b.shape.type) {
    case ShapeType::kSphere: return dir.dot(b.x) + b.shape.radius;
    case ShapeType::kCapsule: {
      const Vec3 half = R * Vec3(0, 0, b.shape.half_length);
      return std::max(dir.dot(b.x + half), dir.dot(b.x - half)) + b.shape.radius;
    }
    case ShapeType::kBox:
      for (const Vec3& v : BoxVertices(b.shape.half_extents)) best = std::max(best, dir.dot(R * v + b.x));
      return best;
    case ShapeType::kConvex:
      for (const Vec3& v : b.shape.hull->vertices) best = std::max(best, dir.dot(R * v + b.x));
      return best;
    default: return best;
  }
}

// Overlap of a and b along n (from A to B): what B must move along n to part.
double Overlap(const RigidBody& a, const RigidBody& b, const Vec3& n) { return Support(a, n) + Support(b, -n); }

struct Tally {
  int collide = 0, apart = 0, band = 0, verdict_mismatch = 0;
  int depth_mismatch = 0, normal_mismatch = 0, ties = 0, undefined_normal = 0;
  int manifold_depth_mismatch = 0, manifold_normal_mismatch = 0, face_preferred = 0;
  int fcl_collide_depth_off = 0;  // FCL collide()'s own depth vs the exact one
  double max_depth_error = 0.0, max_normal_error = 0.0, max_manifold_depth_error = 0.0;
  double max_preferred_excess = 0.0;  // m, overlap along a preferred face minus the minimum
};

using PairMaker = std::function<void(std::mt19937_64&, BodySettings*, BodySettings*)>;

Tally Compare(const PairMaker& make, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Tally t;
  for (int i = 0; i < kPoses; ++i) {
    BodySettings sa, sb;
    make(rng, &sa, &sb);
    const RigidBody a = Make(sa), b = Make(sb);

    fcl::CollisionObjectd oa(FclShape(a), FclPose(a)), ob(FclShape(b), FclPose(b));
    fcl::CollisionRequestd request(1, true);
    fcl::CollisionResultd result;
    fcl::collide(&oa, &ob, request, result);

    Vec3 n_ours = Vec3::Zero();
    const double d = PairSignedDistance(a, b, 1.0, &n_ours);
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
    const Reference ref = ExactReference(a, b);
    if (std::abs(result.getContact(0).penetration_depth - ref.depth) > kTolerance) ++t.fcl_collide_depth_off;

    // the unbiased answer: depth, and a normal along which the overlap is that depth
    const double depth_error = std::abs(-d - ref.depth);
    t.max_depth_error = std::max(t.max_depth_error, depth_error);
    if (depth_error > kTolerance) ++t.depth_mismatch;
    if (ref.normal.isZero()) {
      ++t.undefined_normal;
    } else {
      const double normal_error = (n_ours - ref.normal).norm();
      if (normal_error > kTolerance && std::abs(Overlap(a, b, n_ours) - ref.depth) < kTieTolerance) {
        ++t.ties;  // two directions of the same least overlap
      } else {
        t.max_normal_error = std::max(t.max_normal_error, normal_error);
        if (normal_error > kTolerance) ++t.normal_mismatch;
      }
    }

    // the manifold: its deepest point, and its normal or a preferred face's
    ContactSet contacts;
    Collide(a, 0, b, 1, 0.0, &contacts);
    if (contacts.empty()) {
      ++t.manifold_depth_mismatch;
      continue;
    }
    const Contact& deepest =
        *std::max_element(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) { return x.depth < y.depth; });
    const double manifold_error = std::abs(deepest.depth - ref.depth);
    t.max_manifold_depth_error = std::max(t.max_manifold_depth_error, manifold_error);
    if (manifold_error > kTolerance) ++t.manifold_depth_mismatch;
    if (!ref.normal.isZero() && (deepest.normal - ref.normal).norm() > kTolerance) {
      const double excess = Overlap(a, b, deepest.normal) - ref.depth;
      if (excess < kTolerance) {
        ++t.face_preferred;
        t.max_preferred_excess = std::max(t.max_preferred_excess, excess);
      } else {
        ++t.manifold_normal_mismatch;
      }
    }
  }
  return t;
}

void Report(const char* name, const Tally& t) {
  std::printf("%s: %d colliding, %d apart, %d in the band; verdict mismatches %d\n", name, t.collide, t.apart, t.band,
              t.verdict_mismatch);
  std::printf("  unbiased: depth mismatches %d (max error %.2g m), normal mismatches %d (max error %.2g), "
              "ties %d, undefined reference normals %d\n",
              t.depth_mismatch, t.max_depth_error, t.normal_mismatch, t.max_normal_error, t.ties, t.undefined_normal);
  std::printf("  manifold: depth mismatches %d (max error %.2g m), normal mismatches %d, "
              "preferred faces %d (at most %.2g m deeper)\n",
              t.manifold_depth_mismatch, t.max_manifold_depth_error, t.manifold_normal_mismatch, t.face_preferred,
              t.max_preferred_excess);
  std::printf("  FCL collide() depth off the exact one by > 1e-3: %d\n", t.fcl_collide_depth_off);
}

void ExpectAgreement(const Tally& t) {
  EXPECT_GT(t.collide, 1000);
  EXPECT_GT(t.apart, 1000);
  EXPECT_EQ(t.verdict_mismatch, 0);
  EXPECT_EQ(t.depth_mismatch, 0);
  EXPECT_EQ(t.normal_mismatch, 0);
  EXPECT_EQ(t.manifold_depth_mismatch, 0);
  EXPECT_EQ(t.manifold_normal_mismatch, 0);
  // ties and undefined normals are grazing coincidences, not a way around the check
  EXPECT_LT(t.ties + t.undefined_normal, t.collide / 100);
  EXPECT_LE(t.max_preferred_excess, kSatMaxBias + kSatAbsTolerance + 1e-12);
}

Eigen::Vector4d RandomOrientation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Eigen::Vector4d{u(rng), u(rng), u(rng), u(rng)};
}

Vec3 RandomPosition(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  return Vec3{u(rng), u(rng), u(rng)};
}

BodySettings Box(const Vec3& h) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = h;
  return s;
}

// A fixed shape at the origin and another at a random offset within `spread`.
PairMaker FixedShapes(const BodySettings& shape_a, const BodySettings& shape_b, double spread) {
  return [=](std::mt19937_64& rng, BodySettings* a, BodySettings* b) {
    *a = shape_a;
    *b = shape_b;
    a->orientation = RandomOrientation(rng);
    b->orientation = RandomOrientation(rng);
    b->position = RandomPosition(rng, spread);
  };
}

// Verifies sphere-box against FCL on 10,000 random poses.
TEST(FclOracle, SphereBoxAgreesWithFcl) {
  BodySettings sphere;
  sphere.shape = ShapeType::kSphere;
  sphere.radius = 0.3;
  const Tally t = Compare(FixedShapes(sphere, Box(Vec3(0.4, 0.3, 0.2)), 0.8), 1);
  Report("sphere-box", t);
  ExpectAgreement(t);
}

// Verifies box-box against FCL on 10,000 random poses.
TEST(FclOracle, BoxBoxAgreesWithFcl) {
  const Tally t = Compare(FixedShapes(Box(Vec3(0.5, 0.3, 0.2)), Box(Vec3(0.4, 0.4, 0.1)), 1.2), 2);
  Report("box-box", t);
  ExpectAgreement(t);
}

// Verifies capsule-box against FCL on 10,000 random poses.
TEST(FclOracle, CapsuleBoxAgreesWithFcl) {
  BodySettings capsule;
  capsule.shape = ShapeType::kCapsule;
  capsule.radius = 0.15;
  capsule.half_length = 0.3;
  const Tally t = Compare(FixedShapes(capsule, Box(Vec3(0.4, 0.3, 0.2)), 1.0), 3);
  Report("capsule-box", t);
  ExpectAgreement(t);
}

// Verifies convex-convex against FCL on 10,000 random pairs of hulls of 8-20
// random points (a new pair of hulls every pose).
TEST(FclOracle, ConvexConvexAgreesWithFcl) {
  const auto random_hull = [](std::mt19937_64& rng, BodySettings* s) {
    std::uniform_int_distribution<int> count(8, 20);
    std::uniform_real_distribution<double> u(-0.3, 0.3);
    s->shape = ShapeType::kConvex;
    s->points.resize(count(rng));
    for (Vec3& p : s->points) p = Vec3{u(rng), u(rng), u(rng)};
    s->orientation = RandomOrientation(rng);
  };
  const Tally t = Compare(
      [&](std::mt19937_64& rng, BodySettings* a, BodySettings* b) {
        random_hull(rng, a);
        random_hull(rng, b);
        b->position = RandomPosition(rng, 0.6);
      },
      4);
  Report("convex-convex", t);
  ExpectAgreement(t);
}

}  // namespace
}  // namespace contactsim
