// contactsim-bench-rays: a batch of ray casts against a world of bodies,
// contactsim's RayCastWorld beside Bullet's btCollisionWorld::rayTest over
// the same shapes (Debian libbullet-dev, double precision, DBVT broadphase),
// one thread each. The world: a ground plane and `--bodies` spheres, boxes,
// capsules and 12-point hulls of 0.05-0.5 m at random poses in a 20 m cube;
// the rays: `--rays` from random points of the cube in random directions,
// up to 30 m. Bullet's shapes have zero collision margin, so both answer
// the same geometry; the agreement line counts rays whose first body and
// distance agree. Prints the median thread CPU ms per batch of `--repeat`
// batches, with --json one JSON object. Bullet reports no hit for a ray
// that starts inside a body, contactsim a hit at distance 0.
#include <btBulletCollisionCommon.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "service/collision/ray_cast.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

btVector3 Bt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }

Vec3 Uniform(std::mt19937_64& rng, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  return Vec3{u(rng), u(rng), u(rng)};
}

std::shared_ptr<const ConvexHull> Rock(std::mt19937_64& rng, double size) {
  std::vector<Vec3> points;
  for (int i = 0; i < 12; ++i) points.push_back(Uniform(rng, size));
  std::shared_ptr<const ConvexHull> hull;
  if (!BuildConvexHull(points, &hull).ok()) return nullptr;
  return hull;
}

World MakeWorld(int bodies, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> size(0.05, 0.5);
  std::uniform_int_distribution<int> kind(0, 3);
  std::normal_distribution<double> normal(0.0, 1.0);
  World world;
  RigidBody ground;
  ground.shape = Shape::Plane(Vec3::UnitZ(), 0.0);
  ground.MakeStatic();
  world.AddBody(ground);
  for (int i = 0; i < bodies; ++i) {
    RigidBody b;
    switch (kind(rng)) {
      case 0: b.shape = Shape::Sphere(size(rng)); break;
      case 1: b.shape = Shape::Box(Vec3{size(rng), size(rng), size(rng)}); break;
      case 2: b.shape = Shape::Capsule(size(rng), size(rng)); break;
      default: {
        std::shared_ptr<const ConvexHull> hull = Rock(rng, size(rng));
        b.shape = hull ? Shape::Convex(hull) : Shape::Sphere(0.2);
      }
    }
    b.x = Uniform(rng, 10.0) + Vec3(0, 0, 10.5);
    b.q = Quat{normal(rng), normal(rng), normal(rng), normal(rng)}.normalized();
    world.AddBody(b);
  }
  return world;
}

std::vector<Ray> MakeRays(int n, uint64_t seed) {
  std::mt19937_64 rng(seed + 1);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    while (!MakeRay(Uniform(rng, 12.0) + Vec3(0, 0, 10), Uniform(rng, 1.0), 30.0, &r).ok()) {
    }
  }
  return rays;
}

std::unique_ptr<btCollisionShape> BulletShape(const Shape& s) {
  std::unique_ptr<btCollisionShape> shape;
  switch (s.type) {
    case ShapeType::kSphere: shape = std::make_unique<btSphereShape>(s.radius); break;
    case ShapeType::kBox: shape = std::make_unique<btBoxShape>(Bt(s.half_extents)); break;
    case ShapeType::kCapsule: shape = std::make_unique<btCapsuleShapeZ>(s.radius, 2.0 * s.half_length); break;
    case ShapeType::kConvex: {
      auto hull = std::make_unique<btConvexHullShape>();
      for (const Vec3& v : s.hull->vertices) hull->addPoint(Bt(v), false);
      hull->recalcLocalAabb();
      shape = std::move(hull);
      break;
    }
    case ShapeType::kPlane: shape = std::make_unique<btStaticPlaneShape>(Bt(s.plane_normal), s.plane_offset); break;
    default: break;
  }
  // a sphere's and a capsule's radius is their margin; the others get none
  if (s.type != ShapeType::kSphere && s.type != ShapeType::kCapsule) shape->setMargin(0.0);
  return shape;
}

struct BulletWorld {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btCollisionObject>> objects;

  explicit BulletWorld(const World& w) {
    for (const RigidBody& b : w.bodies()) {
      shapes.push_back(BulletShape(b.shape));
      auto object = std::make_unique<btCollisionObject>();
      btTransform t;
      t.setOrigin(Bt(b.x));
      t.setRotation(btQuaternion(b.q.x(), b.q.y(), b.q.z(), b.q.w()));
      object->setWorldTransform(t);
      object->setCollisionShape(shapes.back().get());
      object->setUserIndex(static_cast<int>(b.id));
      world.addCollisionObject(object.get());
      objects.push_back(std::move(object));
    }
    world.updateAabbs();
  }

  std::vector<RayHit> Cast(const std::vector<Ray>& rays) {
    std::vector<RayHit> hits(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      const btVector3 from = Bt(rays[i].origin), to = Bt(rays[i].origin + rays[i].max_distance * rays[i].direction);
      btCollisionWorld::ClosestRayResultCallback cb(from, to);
      world.rayTest(from, to, cb);
      if (!cb.hasHit()) continue;
      hits[i].hit = true;
      hits[i].body = cb.m_collisionObject->getUserIndex();
      hits[i].distance = cb.m_closestHitFraction * rays[i].max_distance;
    }
    return hits;
  }
};

// The world and rays as JSON, for bench/scripts/ray_bench_pybullet.py.
void Dump(const World& world, const std::vector<Ray>& rays, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return;
  auto vec = [&](const Vec3& v) { std::fprintf(f, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z()); };
  std::fprintf(f, "{\"bodies\": [\n");
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const RigidBody& b = world.bodies()[i];
    const Shape& s = b.shape;
    std::fprintf(f, "%s{\"id\": %lld, \"shape\": \"%s\", \"radius\": %.17g, \"half_length\": %.17g, ",
                 i ? ",\n" : "", static_cast<long long>(b.id), ShapeTypeName(s.type), s.radius, s.half_length);
    std::fprintf(f, "\"half_extents\": ");
    vec(s.half_extents);
    std::fprintf(f, ", \"position\": ");
    vec(b.x);
    std::fprintf(f, ", \"orientation\": [%.17g, %.17g, %.17g, %.17g], \"vertices\": [", b.q.w(), b.q.x(), b.q.y(),
                 b.q.z());
    if (s.type == ShapeType::kConvex) {
      for (size_t k = 0; k < s.hull->vertices.size(); ++k) {
        if (k) std::fprintf(f, ", ");
        vec(s.hull->vertices[k]);
      }
    }
    std::fprintf(f, "]}");
  }
  std::fprintf(f, "],\n\"rays\": [\n");
  for (size_t i = 0; i < rays.size(); ++i) {
    std::fprintf(f, "%s[", i ? ",\n" : "");
    vec(rays[i].origin);
    std::fprintf(f, ", ");
    vec(rays[i].origin + rays[i].max_distance * rays[i].direction);
    std::fprintf(f, "]");
  }
  std::fprintf(f, "]}\n");
  std::fclose(f);
}

// CPU time of this thread (ms): on a machine shared with other work the
// wall clock counts the time the thread waits for a core.
double ThreadMs() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

template <class F>
double MedianMs(int repeat, F&& batch) {
  std::vector<double> ms;
  for (int r = 0; r < repeat; ++r) {
    const double t0 = ThreadMs();
    batch();
    ms.push_back(ThreadMs() - t0);
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace
}  // namespace contactsim

int main(int argc, char** argv) {
  using namespace contactsim;
  CLI::App app{"Ray-cast batches: contactsim beside Bullet's rayTest."};
  int bodies = 1000, rays = 10000, repeat = 9;
  uint64_t seed = 43;
  bool json = false;
  std::string dump;
  app.add_option("--bodies", bodies, "bodies besides the ground")->capture_default_str();
  app.add_option("--rays", rays, "rays per batch")->capture_default_str();
  app.add_option("--repeat", repeat, "batches timed; the median is reported")->capture_default_str();
  app.add_option("--seed", seed, "of the world and the rays")->capture_default_str();
  app.add_flag("--json", json, "one JSON object");
  app.add_option("--dump", dump, "write the world and rays as JSON (for PyBullet's rayTestBatch)");
  CLI11_PARSE(app, argc, argv);

  const World world = MakeWorld(bodies, seed);
  const std::vector<Ray> batch = MakeRays(rays, seed);
  if (!dump.empty()) Dump(world, batch, dump);
  std::vector<RayHit> ours, theirs;
  const double ours_ms = MedianMs(repeat, [&] { ours = RayCastWorld(world, batch, {}, nullptr); });
  BulletWorld bullet(world);
  const double bullet_ms = MedianMs(repeat, [&] { theirs = bullet.Cast(batch); });
  int hits = 0, agree = 0, agree_mm = 0, same_body = 0;
  for (size_t i = 0; i < batch.size(); ++i) {
    hits += ours[i].hit;
    const bool same = ours[i].hit == theirs[i].hit &&
                      (!ours[i].hit || (ours[i].body == theirs[i].body &&
                                        std::abs(ours[i].distance - theirs[i].distance) < 1e-6));
    agree += same;
    if (ours[i].hit == theirs[i].hit && ours[i].body == theirs[i].body) {
      ++same_body;
      agree_mm += !ours[i].hit || std::abs(ours[i].distance - theirs[i].distance) < 1e-3;
    }
  }
  if (json) {
    std::printf("{\"bodies\": %d, \"rays\": %d, \"hits\": %d, \"contactsim_ms\": %.4f, \"bullet_ms\": %.4f, "
                "\"same_body\": %d, \"agree_1mm\": %d, \"agree\": %d}\n",
                bodies, rays, hits, ours_ms, bullet_ms, same_body, agree_mm, agree);
  } else {
    std::printf("%d rays against %d bodies and a plane (%d hit), median thread CPU time of %d batches, one thread:\n", rays, bodies,
                hits, repeat);
    std::printf("  contactsim RayCastWorld      %8.3f ms  (%.3f us a ray, tree built in the batch)\n", ours_ms,
                1000.0 * ours_ms / rays);
    std::printf("  Bullet rayTest (DBVT), each  %8.3f ms  (%.3f us a ray)\n", bullet_ms, 1000.0 * bullet_ms / rays);
    std::printf("  agreement: %d of %d rays hit the same body (or miss alike); %d of them at the same distance to "
                "1e-3 m, %d to 1e-6 m\n",
                same_body, rays, agree_mm, agree);
  }
  return 0;
}
