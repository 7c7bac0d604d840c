// Triangle meshes and heightfields under every registered contact method
// (ContactMethodNames(), lcp with each solver), against a plane and the
// analytic answers:
//  * a box sliding over a flat floor mesh of 20,000 triangles decelerates
//    at mu g as on a plane, for masses 0.1 to 10 kg, in several directions
//    across the triangles' edges (no ghost collision slows it);
//  * a ball rolling over the same floor never lifts off it by 0.1 mm;
//  * a box on a tessellated ramp slides down at g (sin - mu cos) and, pushed
//    up it, slows at g (sin + mu cos) without catching on an edge;
//  * a box resting with a corner on a vertex where triangles meet, a stack
//    of boxes on the mesh, and rocks dropped on a heightfield come to rest
//    (under barrier with its distance above zero at every step).
// A method whose contract lacks triangle surfaces refuses the world. The
// comparisons with the plane hold for every method; a method that misses
// an analytic answer on its plane as well lists it in kKnownMisses.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "service/collision/height_field.h"
#include "service/collision/triangle_mesh.h"
#include "service/physics/body_settings.h"
#include "tests/collision/grid_mesh.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/slope.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::AddValidBody;
using testing::MethodConfig;
using Sim = testing::MethodSim;

Eigen::Vector4d Wxyz(const Quat& q) { return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()); }

// A 10 m square floor of 20,000 triangles (0.1 m cells) through the
// origin, tilted by `angle` about y like AddSlope's plane.
BodyId AddFloorMesh(World& world, double angle, double mu) {
  static const std::shared_ptr<const TriangleMesh> kFloor = testing::BuildGrid(100, 0.1);
  BodySettings s;
  s.shape = ShapeType::kMesh;
  s.mesh = kFloor;
  s.orientation = Wxyz(Quat(Eigen::AngleAxisd(angle, Vec3::UnitY())));
  s.restitution = 0.0;
  s.friction = mu;
  return AddValidBody(world, s);
}

enum class Ground { kPlane, kMesh };

Quat AddGround(World& world, Ground ground, double angle, double mu) {
  Vec3 downhill;
  if (ground == Ground::kPlane) return testing::AddSlope(world, angle, mu, &downhill);
  AddFloorMesh(world, angle, mu);
  return Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()));
}

class SurfaceTest : public ::testing::TestWithParam<MethodConfig> {
 protected:
  const char* Label() const { return GetParam().label.c_str(); }
  // true (the scenario ends) when the method refuses triangle surfaces
  bool Refused(const World& world) const {
    return testing::RefusedByContract(GetParam(), world, testing::ContractOf(GetParam()).triangle_surfaces,
                                      "triangle meshes");
  }
};

// The acceleration along `dir` (m/s^2) of a box of `mass` on the ground
// tilted by `angle`, launched at v0 along `dir` (in the ground's frame)
// after settling, measured between 0.1 s and 0.6 of the time to stop (or
// 0.5 s), away from the launch and the stop.
double BoxAcceleration(const MethodConfig& config, Ground ground, double angle, double mass, double mu,
                       const Vec3& dir_local, double v0, bool* refused, double half = 0.1) {
  Sim sim(config.method, config.params);
  const Quat tilt = AddGround(sim.world, ground, angle, mu);
  *refused = ground == Ground::kMesh && testing::RefusedByContract(config, sim.world,
                                                                   testing::ContractOf(config).triangle_surfaces,
                                                                   "triangle meshes");
  if (*refused) return 0.0;
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(half);
  box.position = tilt * Vec3(0.013, 0.027, half);  // off the grid's lines
  box.orientation = Wxyz(tilt);
  box.mass = mass;
  box.restitution = 0.0;
  box.friction = mu;
  const BodyId id = AddValidBody(sim.world, box);
  for (int i = 0; i < 48; ++i) sim.Step();
  RigidBody& b = *sim.world.Find(id);
  const Vec3 dir = tilt * dir_local;
  b.SetVelocity(b.LinearVelocity() + v0 * dir, Vec3::Zero());
  const double dt = sim.world.dt;
  const int i1 = static_cast<int>(0.1 / dt);
  const int i2 = static_cast<int>(0.6 / dt);
  double v1 = 0.0;
  for (int i = 0; i < i2; ++i) {
    if (i == i1) v1 = sim.world.Find(id)->LinearVelocity().dot(dir);
    sim.Step();
  }
  const double v2 = sim.world.Find(id)->LinearVelocity().dot(dir);
  return (v2 - v1) / ((i2 - i1) * dt);
}

// Verifies no ghost collisions while sliding: a box launched at 4 m/s over
// the 20,000-triangle floor along x, along y and at 30 degrees (across
// edges, diagonals and vertices) decelerates at mu g as on the plane, to
// 0.5% of mu g, for masses 0.1, 1 and 10 kg, and cubes of 5 cm (smaller
// than a cell) and 0.6 m (36 cells) along x.
TEST_P(SurfaceTest, BoxSlidesOverFloorMeshAsOverPlane) {
  testing::MechanicsChecks checks(GetParam().label);
  const double mu = 0.5, v0 = 4.0;
  for (double mass : {0.1, 1.0, 10.0}) {
    for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(std::cos(0.52), std::sin(0.52), 0)}) {
      bool refused = false;
      const double on_mesh = BoxAcceleration(GetParam(), Ground::kMesh, 0.0, mass, mu, dir, v0, &refused);
      if (refused) return;
      const double on_plane = BoxAcceleration(GetParam(), Ground::kPlane, 0.0, mass, mu, dir, v0, &refused);
      std::printf("%s: m %4.1f kg dir (%.2f, %.2f) mesh %.4f plane %.4f mu g %.4f m/s^2\n", Label(), mass, dir.x(),
                  dir.y(), -on_mesh, -on_plane, mu * kG);
      EXPECT_NEAR(on_mesh, on_plane, 0.005 * mu * kG) << Label() << " m " << mass;
      checks.Expect(testing::CaseId("surface slide m=%g dir=%.2f", mass, dir.y()), -on_mesh, mu * kG,
                    0.005 * mu * kG);
    }
  }
  for (double half : {0.025, 0.3}) {
    bool refused = false;
    const double on_mesh = BoxAcceleration(GetParam(), Ground::kMesh, 0.0, 1.0, mu, Vec3::UnitX(), v0, &refused, half);
    const double on_plane = BoxAcceleration(GetParam(), Ground::kPlane, 0.0, 1.0, mu, Vec3::UnitX(), v0, &refused, half);
    std::printf("%s: cube %.2f m mesh %.4f plane %.4f mu g %.4f m/s^2\n", Label(), 2 * half, -on_mesh, -on_plane,
                mu * kG);
    EXPECT_NEAR(on_mesh, on_plane, 0.005 * mu * kG) << Label() << " half " << half;
    checks.Expect(testing::CaseId("surface slide cube=%g", 2 * half), -on_mesh, mu * kG, 0.005 * mu * kG);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies rolling without lift: a ball of radius 0.1 m rolling at 2 m/s
// across the floor mesh (across edges and vertices) never rises more than
// 0.1 mm above where it rested.
TEST_P(SurfaceTest, BallRollsOverFloorMeshWithoutLifting) {
  testing::MechanicsChecks checks(GetParam().label);
  for (double mass : {0.1, 1.0, 10.0}) {
    Sim sim(GetParam().method, GetParam().params);
    AddFloorMesh(sim.world, 0.0, 0.5);
    if (Refused(sim.world)) return;
    BodySettings ball;
    ball.shape = ShapeType::kSphere;
    ball.radius = 0.1;
    ball.position = Vec3(0.013, 0.027, 0.1);
    ball.mass = mass;
    ball.restitution = 0.0;
    ball.friction = 0.5;
    const BodyId id = AddValidBody(sim.world, ball);
    for (int i = 0; i < 48; ++i) sim.Step();
    RigidBody& b = *sim.world.Find(id);
    const double rest = b.x.z();
    const Vec3 v = 2.0 * Vec3(std::cos(0.3), std::sin(0.3), 0.0);
    b.SetVelocity(v, Vec3::UnitZ().cross(v) / 0.1);
    double lift = 0.0;
    for (int i = 0; i < static_cast<int>(1.0 / sim.world.dt); ++i) {
      sim.Step();
      lift = std::max(lift, sim.world.Find(id)->x.z() - rest);
    }
    const double travelled = (sim.world.Find(id)->x - Vec3(0.013, 0.027, rest)).head<2>().norm();
    std::printf("%s: m %4.1f kg rolled %.3f m, largest lift %.3g m\n", Label(), mass, travelled, lift);
    EXPECT_LT(lift, 1e-4) << Label() << " m " << mass;
    // (rolling freely it travels 2 m; 1.5 m bounds any slowing by an edge)
    checks.Expect(testing::CaseId("surface roll m=%g", mass), std::min(travelled, 2.0), 2.0, 0.5);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Prints the cost of the floor mesh (not asserted: wall-clock time): ms a
// step of a 1 kg box sliding at 4 m/s over the 20,000-triangle floor for
// 0.5 s, and over the plane, after it settled; verifies it stayed on the
// floor.
TEST_P(SurfaceTest, PrintsTheCostOfABoxSlidingOverTheFloorMesh) {
  double ms[2] = {0.0, 0.0};
  for (Ground ground : {Ground::kPlane, Ground::kMesh}) {
    Sim sim(GetParam().method, GetParam().params);
    AddGround(sim.world, ground, 0.0, 0.5);
    if (ground == Ground::kMesh && Refused(sim.world)) return;
    BodySettings box;
    box.shape = ShapeType::kBox;
    box.half_extents = Vec3::Constant(0.1);
    box.position = Vec3(0.013, 0.027, 0.1);
    box.mass = 1.0;
    box.restitution = 0.0;
    const BodyId id = AddValidBody(sim.world, box);
    for (int i = 0; i < 48; ++i) sim.Step();
    sim.world.Find(id)->SetVelocity(Vec3(4.0, 0.0, 0.0), Vec3::Zero());
    const int steps = static_cast<int>(0.5 / sim.world.dt);
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) sim.Step();
    const std::chrono::duration<double, std::milli> spent = std::chrono::steady_clock::now() - start;
    ms[ground == Ground::kMesh] = spent.count() / steps;
    EXPECT_NEAR(sim.world.Find(id)->x.z(), 0.1, 2e-3) << Label();
  }
  std::printf("%s: box sliding over the floor mesh %.3f ms/step, over the plane %.3f ms/step\n", Label(), ms[1],
              ms[0]);
}

// Verifies the tessellated ramp: a box released on a ramp of 20 and 30
// degrees (mu 0.2) slides down at g (sin - mu cos), and launched up a ramp
// of 10 and 20 degrees slows at g (sin + mu cos), as on a plane, to 1%.
TEST_P(SurfaceTest, BoxOnTessellatedRampSlidesAtAnalyticAcceleration) {
  testing::MechanicsChecks checks(GetParam().label);
  const double mu = 0.2;
  for (double deg : {10.0, 20.0, 30.0}) {
    const double a = deg * M_PI / 180.0;
    bool refused = false;
    if (deg > 15.0) {
      // tilting +x about y lowers it: +x is downhill
      const double down = BoxAcceleration(GetParam(), Ground::kMesh, a, 1.0, mu, Vec3::UnitX(), 0.0, &refused);
      if (refused) return;
      const double analytic = kG * (std::sin(a) - mu * std::cos(a));
      std::printf("%s: %2.0f deg down %.4f, g (sin - mu cos) %.4f m/s^2\n", Label(), deg, down, analytic);
      checks.Expect(testing::CaseId("surface ramp %g deg down", deg), down, analytic, 0.01 * analytic);
    }
    const double up = BoxAcceleration(GetParam(), Ground::kMesh, a, 1.0, mu, -Vec3::UnitX(), 5.0, &refused);
    if (refused) return;
    const double analytic = -kG * (std::sin(a) + mu * std::cos(a));
    std::printf("%s: %2.0f deg up %.4f, -g (sin + mu cos) %.4f m/s^2\n", Label(), deg, up, analytic);
    checks.Expect(testing::CaseId("surface ramp %g deg up", deg), up, analytic, 0.01 * std::abs(analytic));
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies degenerate placements at rest: a box with its centre on a
// shared vertex of the grid (six triangles meet under it), a box turned
// 45 degrees with a corner on a vertex where four triangles meet, and a
// stack of three boxes, all on the floor mesh: nothing drifts more than
// 1 mm or tilts in 1 s.
TEST_P(SurfaceTest, BoxesRestOnVerticesAndEdgesAndInStacks) {
  Sim sim(GetParam().method, GetParam().params);
  AddFloorMesh(sim.world, 0.0, 0.5);
  if (Refused(sim.world)) return;
  std::vector<BodyId> ids;
  std::vector<Vec3> starts;
  auto add = [&](const Vec3& p, double yaw) {
    BodySettings box;
    box.shape = ShapeType::kBox;
    box.half_extents = Vec3::Constant(0.1);
    box.position = p;
    box.orientation = Wxyz(Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())));
    box.mass = 1.0;
    box.restitution = 0.0;
    ids.push_back(AddValidBody(sim.world, box));
    starts.push_back(p);
  };
  add(Vec3(0.0, 0.0, 0.1), 0.0);                          // centre on a vertex
  add(Vec3(1.0 + 0.1 * std::sqrt(2.0), 0.0, 0.1), M_PI / 4);  // a corner on a vertex
  for (int k = 0; k < 3; ++k) add(Vec3(-1.0, 0.5, 0.1 + 0.2 * k), 0.0);  // a stack
  for (int i = 0; i < static_cast<int>(1.0 / sim.world.dt); ++i) sim.Step();
  for (size_t k = 0; k < ids.size(); ++k) {
    const RigidBody& b = *sim.world.Find(ids[k]);
    const double drift = (b.x - starts[k]).head<2>().norm();
    std::printf("%s: box %zu drift %.3g m, height %.5f m, speed %.3g m/s\n", Label(), k, drift, b.x.z(),
                b.LinearVelocity().norm());
    EXPECT_LT(drift, 1e-3) << Label() << " box " << k;
    EXPECT_NEAR(b.x.z(), starts[k].z(), 2e-3) << Label() << " box " << k;
    EXPECT_LT(b.LinearVelocity().norm(), 0.02) << Label() << " box " << k;
  }
}

// Drops four hulls and boxes of 0.1 to 10 kg from random poses (seed
// `seed`) onto a wavy heightfield and runs 3 s; checks each comes to rest
// on it (below 5 cm/s, none fallen through, no contact deeper than 1 cm at
// the end); under barrier the smallest distance of any pair (its residual)
// stays above zero at every step, its guarantee.
void DropHullsOnWavyField(const MethodConfig& config, uint64_t seed) {
  Sim sim(config.method, config.params);
  const int n = 41;
  std::vector<double> heights;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) heights.push_back(0.05 * std::sin(0.4 * r) * std::cos(0.3 * c));
  }
  std::shared_ptr<const HeightField> field;
  ASSERT_TRUE(BuildHeightField(n, n, heights, 0.1, 0.1, &field).ok());
  BodySettings ground;
  ground.shape = ShapeType::kHeightfield;
  ground.heightfield = field;
  ground.restitution = 0.0;
  AddValidBody(sim.world, ground);
  if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).triangle_surfaces, "triangle meshes")) return;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.2, 1.2), s(0.05, 0.1), angle(-M_PI, M_PI);
  const double masses[4] = {0.1, 1.0, 3.0, 10.0};
  std::vector<BodyId> ids;
  for (int k = 0; k < 4; ++k) {
    BodySettings b;
    b.shape = k % 2 ? ShapeType::kBox : ShapeType::kConvex;
    b.half_extents = Vec3{s(rng), s(rng), s(rng)};
    for (int j = 0; j < 12 && b.shape == ShapeType::kConvex; ++j) {
      // One draw per statement: the order of a call's arguments is unspecified,
      // and g++ and clang would build different scenes from one seed.
      const double radius_x = s(rng), along_x = angle(rng);
      const double radius_y = s(rng), along_y = angle(rng);
      const double height = s(rng) - 0.075;
      b.points.push_back(Vec3{radius_x * std::cos(along_x), radius_y * std::sin(along_y), height});
    }
    b.position = Vec3{u(rng), u(rng), 0.4 + 0.1 * k};
    const double turn = angle(rng);
    b.orientation = Wxyz(Quat(Eigen::AngleAxisd(turn, Vec3{u(rng), u(rng), 1.0}.normalized())));
    b.mass = masses[k % 4];
    b.restitution = 0.0;
    ids.push_back(AddValidBody(sim.world, b));
  }
  const bool intersection_free = config.method == "barrier";
  double closest = std::numeric_limits<double>::infinity();
  StepStats stats;
  for (int i = 0; i < static_cast<int>(3.0 / sim.world.dt); ++i) {
    stats = sim.Step();
    if (intersection_free) closest = std::min(closest, stats.residual);
  }
  const std::string label = config.label + " seed " + std::to_string(seed);
  if (intersection_free) {
    std::printf("%s: smallest distance over the drops %.3g m\n", label.c_str(), closest);
    EXPECT_GT(closest, 0.0) << label;
  }
  EXPECT_LT(stats.max_penetration, 0.01) << label;
  for (BodyId id : ids) {
    const RigidBody& b = *sim.world.Find(id);
    std::printf("%s: body %lld at z %.3f speed %.3g m/s\n", label.c_str(), static_cast<long long>(id), b.x.z(),
                b.LinearVelocity().norm());
    EXPECT_LT(b.LinearVelocity().norm(), 0.05) << label << " body " << id;
    EXPECT_GT(b.x.z(), -0.05) << label << " body " << id;
  }
}

// Verifies random drops on a wavy heightfield (DropHullsOnWavyField) over
// three seeds: valleys and ridges under every kind of landing.
TEST_P(SurfaceTest, RandomDropsComeToRestOnHeightfield) {
  if (const testing::KnownMiss* miss = testing::FindKnownMiss(GetParam().label, "heightfield drops")) {
    GTEST_SKIP() << "known miss: " << miss->why;
  }
  for (uint64_t seed : {11u, 12u, 13u}) DropHullsOnWavyField(GetParam(), seed);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, SurfaceTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
