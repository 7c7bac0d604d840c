#include "bench/tools/scene_bench/scene_metrics.h"

#include <algorithm>
#include <cmath>

#include "service/collision/aabb.h"
#include "service/collision/narrowphase.h"
#include "service/collision/ray_cast.h"

namespace contactsim::bench {
namespace {

constexpr double kFarAway = 1e6;  // m: margin for the ball's height, larger than any scene

bool StateIsFinite(const RigidBody& b) {
  return b.x.allFinite() && b.q.coeffs().allFinite() && b.P.allFinite() && b.L.allFinite();
}

std::string Describe(const RigidBody& b, int index) {
  return b.name.empty() ? "body " + std::to_string(index) : "\"" + b.name + "\"";
}

}  // namespace

void SceneMetrics::Start(const World& world) {
  const auto& bodies = world.bodies();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    start_.push_back(bodies[i].x);
    if (bodies[i].name == "top") top_ = i;
    if (bodies[i].name == "ball") ball_ = i;
    if (plane_ < 0 && bodies[i].shape.IsPlane()) plane_ = i;
    if (bodies[i].shape.IsTriangleSurface()) surfaces_.push_back(i);
  }
  fell_.assign(bodies.size(), false);
  if (top_ >= 0) top_displacement_ = 0.0;
  final_kinetic_energy_ = KineticEnergy(world);
}

std::string SceneMetrics::Check(const World& world) const {
  const auto& bodies = world.bodies();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    const RigidBody& b = bodies[i];
    if (!b.IsDynamic()) continue;
    if (!StateIsFinite(b)) return "nan: " + Describe(b, i) + " has a non-finite state";
    if ((b.x - start_[i]).norm() > kEscapeDistance || b.LinearVelocity().norm() > kEscapeSpeed) {
      return "exploded: " + Describe(b, i) + " left its start by more than 50 m or moved faster than 50 m/s";
    }
  }
  return "";
}

void SceneMetrics::Observe(const World& world) {
  const auto& bodies = world.bodies();
  detector_.Detect(world, kGapMargin, 0.0, &contacts_);
  for (const Contact& c : contacts_) {
    max_penetration_ = std::max(max_penetration_, c.depth);
    min_distance_ = std::min(min_distance_.value_or(kGapMargin), -c.depth);
  }
  FindFallenBodies(world);
  final_kinetic_energy_ = KineticEnergy(world);
  if (top_ >= 0) top_displacement_ = (bodies[top_].x - start_[top_]).norm();
  if (ball_ >= 0 && plane_ >= 0 && bounce_phase_ < 3) {
    const RigidBody& ball = bodies[ball_];
    const RigidBody& plane = bodies[plane_];
    const Vec3 n_W = plane.Rotation() * plane.shape.plane_normal;
    const double height = PairSignedDistance(ball, plane, kFarAway);
    const double v_n = ball.LinearVelocity().dot(n_W);
    if (bounce_phase_ == 0 && v_n < 0.0) bounce_phase_ = 1;
    if (bounce_phase_ == 1 && v_n > 0.0) {
      bounce_phase_ = 2;
      apex_ = height;
    } else if (bounce_phase_ == 2) {
      apex_ = std::max(apex_, height);
      if (v_n <= 0.0) {
        bounce_phase_ = 3;
        rebound_height_ = apex_;
      }
    }
  }
}

std::optional<int> SceneMetrics::fell_through() const {
  if (surfaces_.empty()) return std::nullopt;
  return static_cast<int>(std::count(fell_.begin(), fell_.end(), true));
}

void SceneMetrics::FindFallenBodies(const World& world) {
  const auto& bodies = world.bodies();
  for (const int s : surfaces_) {
    const RigidBody& surface = bodies[s];
    const Aabb box = ComputeAabb(surface, 0.0, 0.0);
    const double above = box.max.z() + 1.0;  // m: the rays start over the whole surface
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
      const RigidBody& b = bodies[i];
      if (!b.IsDynamic() || fell_[i]) continue;
      Ray down;
      if (!MakeRay(Vec3(b.x.x(), b.x.y(), above), -Vec3::UnitZ(), above - box.min.z() + 1.0, &down).ok()) continue;
      const RayHit hit = RayCastBody(surface, down);
      if (hit.hit && hit.point.z() > b.x.z()) fell_[i] = true;
    }
  }
}

}  // namespace contactsim::bench
