// Random convex bodies coming to rest under every registered method
// (method_configs.h): the hull of a seeded random point cloud of 4 points
// (a tetrahedron) to 30, of 0.05 to 0.2 m and 0.1 to 10 kg, of restitution
// 0 and 0.5, placed on its face nearest the centre of mass 5 mm or 10 cm
// above the ground (a barrier method needs a gap at the start), and let
// fall from rest. That face is always stable: the centre of mass projects inside
// it (the foot of the perpendicular from the centre of mass to the nearest
// face plane lies on the surface, or another face plane would be nearer). A body on a stable
// face comes to rest, so after kSettle every body's speed |v| + |w| r
// (r: its farthest vertex from the centre of mass) stays below kRestSpeed
// at every step, and the face it landed on stays down.
//
// A convex hull's contact with the ground is a face of 3 or more points
// rather than a box's 4 symmetric corners, and the face's points lie at
// uneven distances from the centre of mass, so each point carries a
// different share of the weight: a solver that settles a box by symmetry
// can still rock a tetrahedron.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "service/physics/body_settings.h"
#include "service/physics/convex_hull.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/seeded_draw.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::Draw;
using testing::MethodConfig;

constexpr double kSettle = 2.5;        // s to come to rest
constexpr double kWatch = 0.5;         // s after kSettle at rest
constexpr double kRestSpeed = 1e-6;    // m/s, fastest a resting body's point may move
// rad, widest the landing face may tilt from the ground: a body that
// toppled onto another face would tilt by tens of degrees; barrier's
// smooth barrier holds each point of the face at a distance that depends
// on its share of the weight, which tilts it by up to 3e-3 rad
constexpr double kFaceTilt = 0.01;
constexpr int kSeeds = 3;              // hulls per point count

// A hull of `points` random points within a ball of radius `size`, drawn
// again until its volume is at least a tenth of a cube of edge `size` (no
// slivers, whose shape the test is not about).
std::shared_ptr<const ConvexHull> DrawHull(Draw& draw, int points, double size) {
  for (;;) {
    std::vector<Vec3> cloud;
    for (int i = 0; i < points; ++i) {
      Vec3 p = draw.Vector(-1.0, 1.0);
      if (p.norm() < 1e-3) continue;
      const double radius = draw.Uniform(0.5, 1.0) * size;
      cloud.push_back(p.normalized() * radius);
    }
    std::shared_ptr<const ConvexHull> hull;
    if (static_cast<int>(cloud.size()) == points && BuildConvexHull(cloud, &hull).ok() &&
        ConvexHullVolume(*hull) >= 0.1 * size * size * size) {
      return hull;
    }
  }
}

// The index of the hull's face nearest the centre of mass (the origin).
int NearestFace(const ConvexHull& hull) {
  int best = 0;
  for (size_t f = 1; f < hull.faces.size(); ++f) {
    if (hull.faces[f].offset < hull.faces[best].offset) best = static_cast<int>(f);
  }
  return best;
}

struct Rest {
  double speed = 0.0;  // m/s, fastest |v| + |w| r after kSettle
  double tilt = 0.0;   // rad, the landing face's normal from -z at the end
};

Rest DropHull(testing::MethodSim& sim, const ConvexHull& hull, double mass, double restitution, double drop) {
  testing::AddGround(sim.world, restitution, 0.5);
  const ConvexHull::Face& face = hull.faces[NearestFace(hull)];
  const Quat down = Quat::FromTwoVectors(face.normal, Vec3(0, 0, -1));
  BodySettings s;
  s.shape = ShapeType::kConvex;
  s.points = hull.vertices;
  s.mass = mass;
  s.restitution = restitution;
  s.friction = 0.5;
  s.position = Vec3(0, 0, face.offset + drop);
  s.orientation = Eigen::Vector4d(down.w(), down.x(), down.y(), down.z());
  const BodyId id = testing::AddValidBody(sim.world, s);
  double reach = 0.0;  // m
  for (const Vec3& v : hull.vertices) reach = std::max(reach, v.norm());
  Rest rest;
  const int settle = static_cast<int>(std::lround(kSettle / sim.world.dt));
  const int watch = static_cast<int>(std::lround(kWatch / sim.world.dt));
  for (int i = 0; i < settle + watch; ++i) {
    sim.Step();
    if (i < settle) continue;
    const RigidBody& b = *sim.world.Find(id);
    rest.speed = std::max(rest.speed, b.LinearVelocity().norm() + b.AngularVelocity().norm() * reach);
  }
  const RigidBody& b = *sim.world.Find(id);
  const Vec3 normal = b.q * face.normal;
  rest.tilt = std::atan2(normal.cross(Vec3(0, 0, -1)).norm(), -normal.z());
  return rest;
}

using HullParam = std::tuple<MethodConfig, int>;  // method, points in the cloud

class RestingHullTest : public ::testing::TestWithParam<HullParam> {};

// Verifies kRestSpeed and kFaceTilt for kSeeds hulls of the case's point
// count, each of a drawn size and mass, at each restitution and drop height.
TEST_P(RestingHullTest, RandomHullComesToRestOnAFace) {
  const auto& [config, points] = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (int seed = 1; seed <= kSeeds; ++seed) {
    Draw draw(1000u * static_cast<unsigned>(points) + static_cast<unsigned>(seed));
    const double size = draw.Uniform(0.05, 0.2);
    const double mass = std::exp(draw.Uniform(std::log(0.1), std::log(10.0)));
    const std::shared_ptr<const ConvexHull> hull = DrawHull(draw, points, size);
    for (const double e : {0.0, 0.5}) {
      for (const double drop : {0.005, 0.1}) {
        testing::MethodSim sim(config.method, config.params);
        const Rest rest = DropHull(sim, *hull, mass, e, drop);
        char id[96];
        std::snprintf(id, sizeof(id), "hull of %d points seed %d e=%g drop %g m", points, seed, e, drop);
        std::printf("%-10s %s (%zu faces, %.3f m, %.2f kg): speed %.2e m/s, tilt %.2e rad\n", config.label.c_str(),
                    id, hull->faces.size(), size, mass, rest.speed, rest.tilt);
        checks.Expect(std::string(id) + " speed", rest.speed, 0.0, kRestSpeed);
        checks.Expect(std::string(id) + " tilt", rest.tilt, 0.0, kFaceTilt);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

class RestingTetrahedronTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies kRestSpeed and kFaceTilt for tetrahedra (the hull whose face
// splits the weight most unevenly among the fewest points) of three more
// shapes, each at 0.1 and 10 kg and at 0.05 and 0.2 m (one drawn shape
// scaled: the draws do not depend on the size), with restitution 0 and 0.5,
// dropped 5 mm: lcp's projected Gauss-Seidel rocked such bodies at its
// tolerance until it took two sweeps a step (pgs.h, "Warm-started solves").
TEST_P(RestingTetrahedronTest, TetrahedronComesToRestAtEveryMassAndSize) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (int seed = kSeeds + 1; seed <= 2 * kSeeds; ++seed) {
    for (const double size : {0.05, 0.2}) {
      Draw draw(4000u + static_cast<unsigned>(seed));
      const std::shared_ptr<const ConvexHull> hull = DrawHull(draw, 4, size);
      for (const double mass : {0.1, 10.0}) {
        for (const double e : {0.0, 0.5}) {
          testing::MethodSim sim(config.method, config.params);
          const Rest rest = DropHull(sim, *hull, mass, e, 0.005);
          char id[96];
          std::snprintf(id, sizeof(id), "hull of 4 points seed %d m=%g size=%g e=%g", seed, mass, size, e);
          std::printf("%-10s %s: speed %.2e m/s, tilt %.2e rad\n", config.label.c_str(), id, rest.speed, rest.tilt);
          checks.Expect(std::string(id) + " speed", rest.speed, 0.0, kRestSpeed);
          checks.Expect(std::string(id) + " tilt", rest.tilt, 0.0, kFaceTilt);
        }
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, RestingTetrahedronTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

std::string HullName(const ::testing::TestParamInfo<HullParam>& info) {
  return std::get<0>(info.param).label + "_" + std::to_string(std::get<1>(info.param)) + "Points";
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, RestingHullTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(4, 5, 8, 15, 30)),
                         HullName);

}  // namespace
}  // namespace contactsim
