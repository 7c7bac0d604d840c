// Ray casts against each shape, checked against an independent reference:
// every shape is {p : g(p) <= 0} for a convex g whose zero set is its surface
// (distance to the sphere's centre or the capsule's segment minus the radius,
// the largest face-plane distance of a box or hull), so along a ray g is a
// convex function of t: its minimum says hit or miss, and bisection between
// the origin and that minimum finds the entry to round-off. A batch against
// a world of 1,000 bodies equals testing every body, for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "service/collision/ray_cast.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Hull;
using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::RandomVector;

constexpr double kRayTol = 1e-9;  // m

// g of the body's shape at a world point (see the file comment).
double Implicit(const RigidBody& body, const Vec3& p_W) {
  const Vec3 p = body.q.conjugate() * (p_W - body.x);
  const Shape& s = body.shape;
  switch (s.type) {
    case ShapeType::kSphere: return p.norm() - s.radius;
    case ShapeType::kBox: return (p.cwiseAbs() - s.half_extents).maxCoeff();
    case ShapeType::kCapsule: {
      const Vec3 c(0, 0, std::clamp(p.z(), -s.half_length, s.half_length));
      return (p - c).norm() - s.radius;
    }
    case ShapeType::kConvex: {
      double g = -1e300;
      for (const ConvexHull::Face& f : s.hull->faces) g = std::max(g, f.normal.dot(p) - f.offset);
      return g;
    }
    case ShapeType::kPlane: return s.plane_normal.dot(p) - s.plane_offset;
    default: return 1e300;
  }
}

struct Reference {
  bool ambiguous = false;  // the ray grazes the surface: hit and miss are both right
  bool hit = false;
  double t = 0.0;
};

Reference ReferenceEntry(const RigidBody& body, const Ray& ray) {
  auto g = [&](double t) { return Implicit(body, ray.origin + t * ray.direction); };
  Reference ref;
  if (g(0.0) <= 0.0) {
    ref.hit = true;
    return ref;
  }
  double lo = 0.0, hi = ray.max_distance;  // ternary search for the minimum of a convex g
  for (int i = 0; i < 300; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (g(m1) < g(m2)) hi = m2;
    else lo = m1;
  }
  const double t_min = 0.5 * (lo + hi);
  if (std::abs(g(t_min)) < 1e-7) ref.ambiguous = true;
  if (g(t_min) > 0.0) return ref;
  double a = 0.0, b = t_min;  // g(a) > 0 >= g(b)
  for (int i = 0; i < 200 && a < b; ++i) {
    const double m = 0.5 * (a + b);
    if (m == a || m == b) break;
    (g(m) > 0.0 ? a : b) = m;
  }
  ref.hit = true;
  ref.t = b;
  return ref;
}

Ray MakeTestRay(const Vec3& o, const Vec3& d, double max_distance) {
  Ray ray;
  EXPECT_TRUE(MakeRay(o, d, max_distance, &ray).ok());
  return ray;
}

// The answer of RayCastBody against the reference: hit or miss, distance
// and point; the normal is unit, faces the ray and points out of the solid.
void ExpectMatchesReference(const RigidBody& body, const Ray& ray, int* hits, int* ambiguous) {
  const RayHit h = RayCastBody(body, ray);
  const Reference ref = ReferenceEntry(body, ray);
  if (ref.ambiguous) {
    ++*ambiguous;
    return;
  }
  ASSERT_EQ(h.hit, ref.hit) << ShapeTypeName(body.shape.type) << " o " << ray.origin.transpose() << " d "
                            << ray.direction.transpose();
  if (!h.hit) return;
  ++*hits;
  EXPECT_EQ(h.body, body.id);
  EXPECT_NEAR(h.distance, ref.t, kRayTol) << ShapeTypeName(body.shape.type);
  EXPECT_NEAR((h.point - (ray.origin + ref.t * ray.direction)).norm(), 0.0, kRayTol);
  EXPECT_NEAR(h.normal.norm(), 1.0, 1e-12);
  if (ref.t == 0.0) {
    EXPECT_EQ(h.normal, -ray.direction);
    return;
  }
  EXPECT_NEAR(Implicit(body, h.point), 0.0, kRayTol);
  EXPECT_LT(h.normal.dot(ray.direction), 0.0);
  // the normal points out of the solid: a step along it leaves it
  const Vec3 just_out = h.point + 1e-7 * h.normal;
  EXPECT_GT(Implicit(body, just_out), 0.0);
}

std::vector<RigidBody> ShapesUnderTest(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.1, 2.0);
  const Quat q = RandomRotation(rng);
  const Vec3 x = RandomVector(rng, 3.0);
  return {
      MakeBody(1, Shape::Sphere(size(rng)), x, q),
      MakeBody(2, Shape::Box(Vec3{size(rng), size(rng), size(rng)}), x, q),
      MakeBody(3, Shape::Capsule(size(rng), size(rng)), x, q),
      MakeBody(4, Shape::Convex(testing_util::RockHull()), x, q),
      MakeBody(5, Shape::Convex(Hull({{-1, -1, -1}, {2, 0, 0}, {0, 1.5, 0}, {0, 0, 1}, {0.5, 0.5, 0.8}})), x, q),
      MakeBody(6, Shape::Plane(RandomRotation(rng) * Vec3::UnitZ(), size(rng)), x, q),
  };
}

// Verifies 100 random rays per shape, aimed near the body from up to 6 m
// away (most hit, some miss, some start inside), against the reference.
TEST(RayCastTest, RandomRaysMatchTheReferenceOnEveryShape) {
  std::mt19937_64 rng(43);
  for (int pose = 0; pose < 5; ++pose) {
    for (const RigidBody& body : ShapesUnderTest(rng)) {
      int hits = 0, ambiguous = 0;
      for (int i = 0; i < 100; ++i) {
        const Vec3 o = body.x + RandomVector(rng, 6.0);
        const Vec3 aim = body.x + RandomVector(rng, i % 2 == 0 ? 0.1 : 2.0);  // half near the centre
        ExpectMatchesReference(body, MakeTestRay(o, aim - o, 20.0), &hits, &ambiguous);
      }
      EXPECT_GT(hits, 40) << ShapeTypeName(body.shape.type);
      EXPECT_LT(ambiguous, 3) << ShapeTypeName(body.shape.type);
    }
  }
}

// Verifies rays aimed exactly at a box's and a hull's corners and edge
// midpoints from outside: the entry is the corner or the edge point.
TEST(RayCastTest, RaysAtCornersAndEdgesEnterThere) {
  std::mt19937_64 rng(7);
  const Vec3 h(0.3, 0.7, 1.1);
  const RigidBody box = MakeBody(1, Shape::Box(h), Vec3(1, -2, 0.5), RandomRotation(rng));
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      for (int sz : {-1, 1}) {
        const Vec3 corner_B(sx * h.x(), sy * h.y(), sz * h.z());
        for (const Vec3& target_B : {corner_B, Vec3(sx * h.x(), sy * h.y(), 0.0)}) {
          const Vec3 target = box.x + box.q * target_B;
          const Vec3 away = box.q * (corner_B.cwiseSign() + Vec3(0.1, 0.2, 0.3).cwiseProduct(corner_B.cwiseSign()));
          const Vec3 o = target + 2.0 * away;
          const RayHit hit = RayCastBody(box, MakeTestRay(o, target - o, 10.0));
          ASSERT_TRUE(hit.hit);
          EXPECT_NEAR((hit.point - target).norm(), 0.0, kRayTol);
          EXPECT_NEAR(hit.distance, (target - o).norm(), kRayTol);
        }
      }
    }
  }
  const RigidBody rock = MakeBody(2, Shape::Convex(testing_util::RockHull()), Vec3(0, 1, 2), RandomRotation(rng));
  for (const Vec3& v_B : rock.shape.hull->vertices) {
    const Vec3 v = rock.x + rock.q * v_B;
    const Vec3 o = v + 3.0 * (rock.q * v_B).normalized();
    const RayHit hit = RayCastBody(rock, MakeTestRay(o, v - o, 10.0));
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR((hit.point - v).norm(), 0.0, kRayTol);
  }
}

// Verifies rays parallel to a box's faces: inside the slab they hit the
// facing side, a hair outside it they miss, exactly on a face they touch it.
TEST(RayCastTest, RaysParallelToFacesHitOrMissByTheSlab) {
  const RigidBody box = MakeBody(1, Shape::Box(Vec3(1, 2, 3)), Vec3(10, 0, 0));
  for (double y : {-2.5, -2.0 - 1e-9, -2.0, -1.0, 0.0, 1.999999, 2.0, 2.0 + 1e-9}) {
    const RayHit hit = RayCastBody(box, MakeTestRay(Vec3(0, y, 0), Vec3(1, 0, 0), 100.0));
    const bool inside_slab = std::abs(y) <= 2.0;
    ASSERT_EQ(hit.hit, inside_slab) << y;
    if (!hit.hit) continue;
    EXPECT_EQ(hit.distance, 9.0);
    EXPECT_EQ(hit.normal, Vec3(-1, 0, 0));
  }
}

// Verifies the answer for origins inside or on a solid (distance 0, the
// normal against the ray, for every shape) and for max_distance 0 (a hit
// only from inside).
TEST(RayCastTest, RaysFromInsideHitAtZeroAgainstTheRay) {
  std::mt19937_64 rng(3);
  for (const RigidBody& body : ShapesUnderTest(rng)) {
    const Vec3 d = Vec3(0.3, -0.4, 0.5).normalized();
    Vec3 inside = body.x;
    if (body.shape.IsPlane()) inside = body.q * (body.shape.plane_normal * (body.shape.plane_offset - 1.0)) + body.x;
    for (double max_distance : {0.0, 5.0}) {
      const RayHit hit = RayCastBody(body, MakeTestRay(inside, d, max_distance));
      ASSERT_TRUE(hit.hit) << ShapeTypeName(body.shape.type);
      EXPECT_EQ(hit.distance, 0.0);
      EXPECT_EQ(hit.point, inside);
      EXPECT_NEAR((hit.normal + d).norm(), 0.0, 1e-15);
    }
    const Vec3 outside = inside + 100.0 * (body.shape.IsPlane() ? body.q * body.shape.plane_normal : d);
    EXPECT_FALSE(RayCastBody(body, MakeTestRay(outside, -d, 0.0)).hit) << ShapeTypeName(body.shape.type);
  }
  // on the surface counts as inside: a ray leaving a sphere from its surface
  const RigidBody ball = MakeBody(1, Shape::Sphere(1.0), Vec3::Zero());
  const RayHit on = RayCastBody(ball, MakeTestRay(Vec3(1, 0, 0), Vec3(1, 0, 0), 1.0));
  ASSERT_TRUE(on.hit);
  EXPECT_EQ(on.distance, 0.0);
}

// Verifies a ray that would hit beyond max_distance misses, and one whose
// entry is exactly at max_distance hits.
TEST(RayCastTest, MaxDistanceBoundsTheHit) {
  const RigidBody box = MakeBody(1, Shape::Box(Vec3(1, 1, 1)), Vec3(5, 0, 0));
  EXPECT_FALSE(RayCastBody(box, MakeTestRay(Vec3::Zero(), Vec3::UnitX(), 3.999)).hit);
  EXPECT_TRUE(RayCastBody(box, MakeTestRay(Vec3::Zero(), Vec3::UnitX(), 4.0)).hit);
}

// Verifies that garbage rays are refused with a message naming the field.
TEST(RayCastTest, MakeRayRefusesGarbage) {
  Ray ray;
  const double nan = std::nan("");
  EXPECT_NE(MakeRay(Vec3(nan, 0, 0), Vec3::UnitX(), 1, &ray).message().find("origin"), std::string::npos);
  EXPECT_NE(MakeRay(Vec3::Zero(), Vec3(0, nan, 0), 1, &ray).message().find("direction"), std::string::npos);
  EXPECT_NE(MakeRay(Vec3::Zero(), Vec3::Zero(), 1, &ray).message().find("length"), std::string::npos);
  EXPECT_NE(MakeRay(Vec3::Zero(), Vec3::UnitX(), -1, &ray).message().find("max_distance"), std::string::npos);
  EXPECT_NE(MakeRay(Vec3::Zero(), Vec3::UnitX(), INFINITY, &ray).message().find("max_distance"),
            std::string::npos);
  EXPECT_FALSE(MakeRay(Vec3::Zero(), Vec3::UnitX(), nan, &ray).ok());
  ASSERT_TRUE(MakeRay(Vec3::Zero(), Vec3(0, 0, 2), 1, &ray).ok());
  EXPECT_EQ(ray.direction, Vec3::UnitZ());
}

World ThousandBodyWorld(std::mt19937_64& rng) {
  World world;
  world.AddBody(MakeBody(0, Shape::Plane(Vec3::UnitZ(), 0.0)));
  std::uniform_real_distribution<double> size(0.05, 0.5);
  std::uniform_int_distribution<int> kind(0, 4);
  for (int i = 0; i < 1000; ++i) {
    Shape shape;
    switch (kind(rng)) {
      case 4:
        shape = Shape::Compound(std::vector<ShapeChild>{
            {Shape::Sphere(size(rng)), Vec3(-0.3, 0, 0), Quat::Identity()},
            {Shape::Box(Vec3{size(rng), size(rng), size(rng)}), Vec3(0.3, 0, 0), RandomRotation(rng)}});
        break;
      case 0: shape = Shape::Sphere(size(rng)); break;
      case 1: shape = Shape::Box(Vec3{size(rng), size(rng), size(rng)}); break;
      case 2: shape = Shape::Capsule(size(rng), size(rng)); break;
      default: shape = Shape::Convex(testing_util::RockHull()); break;
    }
    world.AddBody(MakeBody(0, shape, RandomVector(rng, 10.0) + Vec3(0, 0, 10.5), RandomRotation(rng)));
  }
  return world;
}

std::vector<Ray> RandomRays(std::mt19937_64& rng, int n) {
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    EXPECT_TRUE(MakeRay(RandomVector(rng, 12.0) + Vec3(0, 0, 10), RandomVector(rng, 1.0), 30.0, &r).ok());
  }
  return rays;
}

void ExpectSameHits(const std::vector<RayHit>& a, const std::vector<RayHit>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].hit, b[i].hit) << i;
    EXPECT_EQ(a[i].body, b[i].body) << i;
    EXPECT_EQ(a[i].distance, b[i].distance) << i;
    EXPECT_EQ(a[i].point, b[i].point) << i;
    EXPECT_EQ(a[i].normal, b[i].normal) << i;
  }
}

// Verifies that the tree's batch equals every ray against every body bit
// for bit, serially and on 4 threads, with and without ignored bodies.
TEST(RayCastTest, BatchOverAThousandBodiesEqualsBruteForce) {
  std::mt19937_64 rng(1000);
  const World world = ThousandBodyWorld(rng);
  const std::vector<Ray> rays = RandomRays(rng, 2000);
  RayCastOptions options;
  const std::vector<RayHit> brute = RayCastBruteForce(world, rays, options);
  int hits = 0;
  for (const RayHit& h : brute) hits += h.hit;
  EXPECT_GT(hits, 1000);
  ExpectSameHits(RayCastWorld(world, rays, options, nullptr), brute);
  ParallelRunner four(4);
  ExpectSameHits(RayCastWorld(world, rays, options, &four), brute);

  for (BodyId id = 1; id <= 1001; id += 3) options.ignore.push_back(id);
  const std::vector<RayHit> brute_ignoring = RayCastBruteForce(world, rays, options);
  ExpectSameHits(RayCastWorld(world, rays, options, &four), brute_ignoring);
  for (const RayHit& h : brute_ignoring) EXPECT_FALSE(h.hit && (h.body - 1) % 3 == 0);
}

// Verifies a compound of two spheres (at x = -1 and x = +1, radius 0.5)
// and a box, turned and moved: the nearer child is hit, from inside any
// child the hit is at 0, between the children the ray passes.
TEST(RayCastTest, CompoundsAreCastChildByChild) {
  std::mt19937_64 rng(11);
  const Quat q = RandomRotation(rng);
  const Vec3 x(0.3, -0.2, 1.0);
  std::vector<ShapeChild> children = {{Shape::Sphere(0.5), Vec3(-1, 0, 0), Quat::Identity()},
                                      {Shape::Sphere(0.5), Vec3(1, 0, 0), Quat::Identity()},
                                      {Shape::Box(Vec3(0.1, 0.2, 0.3)), Vec3(0, 0, 2), RandomRotation(rng)}};
  const RigidBody body = MakeBody(1, Shape::Compound(children), x, q);
  auto world_point = [&](const Vec3& p) -> Vec3 { return x + q * p; };
  // along -x from x = 5: the +x sphere's far side at 1.5
  RayHit h = RayCastBody(body, MakeTestRay(world_point(Vec3(5, 0, 0)), q * Vec3(-1, 0, 0), 10));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance, 3.5, kRayTol);
  EXPECT_NEAR((h.normal - q * Vec3(1, 0, 0)).norm(), 0.0, kRayTol);
  // along y between the spheres, below the box: nothing
  EXPECT_FALSE(RayCastBody(body, MakeTestRay(world_point(Vec3(0, -5, 0)), q * Vec3(0, 1, 0), 10)).hit);
  // from inside the -x sphere
  h = RayCastBody(body, MakeTestRay(world_point(Vec3(-1.1, 0, 0)), q * Vec3(0, 0, 1), 10));
  ASSERT_TRUE(h.hit);
  EXPECT_EQ(h.distance, 0.0);
  // down onto the box from above: its top face, turned by the child's and the body's rotation
  const ShapeChild& box = children[2];
  const Vec3 top = box.position + box.orientation * Vec3(0, 0, 0.3);
  const Vec3 up = box.orientation * Vec3(0, 0, 1);
  h = RayCastBody(body, MakeTestRay(world_point(top + 2.0 * up), q * -up, 10));
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distance, 2.0, kRayTol);
  EXPECT_NEAR((h.normal - q * up).norm(), 0.0, kRayTol);
}

// Verifies the mask: a body whose category shares no bit with it is passed.
TEST(RayCastTest, MaskSelectsBodiesByCategory) {
  World world;
  RigidBody near = MakeBody(0, Shape::Sphere(0.5), Vec3(2, 0, 0));
  near.collision_category = 0x2;
  const BodyId near_id = world.AddBody(near);
  const BodyId far_id = world.AddBody(MakeBody(0, Shape::Sphere(0.5), Vec3(5, 0, 0)));
  const std::vector<Ray> rays = {MakeTestRay(Vec3::Zero(), Vec3::UnitX(), 10)};
  RayCastOptions options;
  EXPECT_EQ(RayCastWorld(world, rays, options, nullptr)[0].body, near_id);
  options.mask = 0x1;
  EXPECT_EQ(RayCastWorld(world, rays, options, nullptr)[0].body, far_id);
  EXPECT_EQ(RayCastBruteForce(world, rays, options)[0].body, far_id);
  options.mask = 0x4;
  EXPECT_FALSE(RayCastWorld(world, rays, options, nullptr)[0].hit);
}

// Verifies an empty world and an empty batch.
TEST(RayCastTest, EmptyWorldAndEmptyBatch) {
  World world;
  std::mt19937_64 rng(1);
  const std::vector<Ray> rays = RandomRays(rng, 10);
  for (const RayHit& h : RayCastWorld(world, rays, {}, nullptr)) EXPECT_FALSE(h.hit);
  EXPECT_TRUE(RayCastWorld(world, {}, {}, nullptr).empty());
}

}  // namespace
}  // namespace contactsim
