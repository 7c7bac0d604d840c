#include "service/collision/ray_cast.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "service/collision/aabb.h"
#include "service/collision/box_tree.h"
#include "service/collision/ray_shape.h"

namespace contactsim {
namespace {

// The nearer of two hits: by distance, then by the smaller body id, so that
// the answer does not depend on the order bodies are tested in.
bool Nearer(const RayHit& a, const RayHit& b) {
  if (!a.hit) return false;
  if (!b.hit) return true;
  return a.distance < b.distance || (a.distance == b.distance && a.body < b.body);
}

bool Ignored(const std::vector<BodyId>& sorted_ignore, uint32_t mask, const RigidBody& body) {
  return (body.collision_category & mask) == 0 ||
         std::binary_search(sorted_ignore.begin(), sorted_ignore.end(), body.id);
}

std::vector<BodyId> SortedIgnore(const RayCastOptions& options) {
  std::vector<BodyId> ids = options.ignore;
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace

Status MakeRay(const Vec3& origin, const Vec3& direction, double max_distance, Ray* ray) {
  if (!IsFinite(origin)) return Status::InvalidArgument("ray origin is not finite");
  if (!IsFinite(direction)) return Status::InvalidArgument("ray direction is not finite");
  const double length = direction.norm();
  if (!(length > 1e-12)) {
    return Status::InvalidArgument("ray direction has length " + std::to_string(length) + ", needs > 1e-12");
  }
  if (!std::isfinite(max_distance) || max_distance < 0.0) {
    return Status::InvalidArgument("ray max_distance " + std::to_string(max_distance) +
                                   " must be finite and >= 0");
  }
  ray->origin = origin;
  ray->direction = direction / length;
  ray->max_distance = max_distance;
  return Status::Ok();
}

RayHit RayCastBody(const RigidBody& body, const Ray& ray) {
  const Quat to_body = body.q.conjugate();
  const Vec3 o = to_body * (ray.origin - body.x);
  const Vec3 u = to_body * ray.direction;
  RayShapeHit h;
  RayHit out;
  switch (RayCastShape(body.shape, o, u, ray.max_distance, &h)) {
    case RayShapeResult::kMiss: return out;
    case RayShapeResult::kInside:
      out.distance = 0.0;
      out.point = ray.origin;
      out.normal = -ray.direction;
      break;
    case RayShapeResult::kHit:
      out.distance = h.t;
      out.point = ray.origin + h.t * ray.direction;
      out.normal = body.q * h.normal;
      break;
  }
  out.hit = true;
  out.body = body.id;
  return out;
}

std::vector<RayHit> RayCastWorld(const World& world, const std::vector<Ray>& rays, const RayCastOptions& options,
                                 ParallelRunner* runner) {
  const std::vector<RigidBody>& bodies = world.bodies();
  const std::vector<BodyId> ignore = SortedIgnore(options);
  std::vector<int> planes, solids;
  std::vector<Aabb> boxes;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    if (Ignored(ignore, options.mask, bodies[i])) continue;
    if (bodies[i].shape.IsPlane()) {
      planes.push_back(i);
    } else {
      solids.push_back(i);
      boxes.push_back(ComputeAabb(bodies[i], 0.0, 0.0));
    }
  }
  BoxTree bvh;
  bvh.Build(boxes);
  std::vector<RayHit> hits(rays.size());
  auto cast = [&](int begin, int end, int /*worker*/) {
    for (int r = begin; r < end; ++r) {
      const Ray& ray = rays[r];
      RayHit best;
      for (int i : planes) {
        const RayHit h = RayCastBody(bodies[i], ray);
        if (Nearer(h, best)) best = h;
      }
      double reach = best.hit ? best.distance : ray.max_distance;
      bvh.Walk(ray.origin, ray.direction, &reach, [&](int item, double* limit) {
        const RayHit h = RayCastBody(bodies[solids[item]], ray);
        if (!Nearer(h, best)) return;
        best = h;
        *limit = h.distance;
      });
      hits[r] = best;
    }
  };
  const int n = static_cast<int>(rays.size());
  if (runner != nullptr) {
    runner->For(n, 64, cast);
  } else {
    cast(0, n, 0);
  }
  return hits;
}

std::vector<RayHit> RayCastBruteForce(const World& world, const std::vector<Ray>& rays,
                                      const RayCastOptions& options) {
  const std::vector<BodyId> ignore = SortedIgnore(options);
  std::vector<RayHit> hits(rays.size());
  for (size_t r = 0; r < rays.size(); ++r) {
    for (const RigidBody& b : world.bodies()) {
      if (Ignored(ignore, options.mask, b)) continue;
      const RayHit h = RayCastBody(b, rays[r]);
      if (Nearer(h, hits[r])) hits[r] = h;
    }
  }
  return hits;
}

}  // namespace contactsim
