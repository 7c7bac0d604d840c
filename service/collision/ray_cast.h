// Ray casts against the world: a batch of rays, each answered with the
// nearest body it hits (ray_shape.h says how a ray starting inside a body is
// answered: a hit at distance 0 with the normal against the ray).
//
// A batch builds one bounding-volume tree over the bodies' boxes
// (box_tree.h) and walks it per ray, nearest box first, so that 10,000 rays
// against 1,000 bodies test a few bodies per ray rather than every pair;
// planes, whose boxes span the world, are tested apart by every ray. Each
// ray writes its own slot, and the nearest hit is chosen by (distance, body
// id), so the answers are the same for any thread count and equal, bit for
// bit, to testing every body in id order (RayCastBruteForce).
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/physics/math.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

struct Ray {
  Vec3 origin = Vec3::Zero();     // m, world
  Vec3 direction = Vec3::UnitX(); // unit, world (MakeRay normalises)
  double max_distance = 0.0;      // m, >= 0
};

struct RayHit {
  bool hit = false;
  BodyId body = 0;                // 0 when no hit
  Vec3 point = Vec3::Zero();      // m, world: origin + distance * direction
  Vec3 normal = Vec3::Zero();     // unit, world, the surface's outward normal (-direction from inside)
  double distance = 0.0;          // m along the ray
};

struct RayCastOptions {
  std::vector<BodyId> ignore;     // bodies the rays pass through (a sensor's own body)
  // Only bodies whose collision_category shares a bit with the mask are hit
  // (collision_filter.h's categories); all bits: every body.
  uint32_t mask = 0xFFFFFFFFu;
};

// Checks one ray as it arrives (finite origin and direction, a direction
// longer than 1e-12, a finite max_distance >= 0) and normalises its
// direction; on error the message names what was wrong.
Status MakeRay(const Vec3& origin, const Vec3& direction, double max_distance, Ray* ray);

// The nearest hit of one ray on one body (hit = false when it misses).
RayHit RayCastBody(const RigidBody& body, const Ray& ray);

// The nearest hit of each ray, in the rays' order; `runner` may be null
// (serial).
std::vector<RayHit> RayCastWorld(const World& world, const std::vector<Ray>& rays, const RayCastOptions& options,
                                 ParallelRunner* runner);

// Every ray against every body in id order: the reference RayCastWorld
// equals.
std::vector<RayHit> RayCastBruteForce(const World& world, const std::vector<Ray>& rays,
                                      const RayCastOptions& options);

}  // namespace contactsim
