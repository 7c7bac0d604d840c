// Compound bodies and explicit mass properties under every registered
// contact method (method_configs.h), or its contract's refusal:
//  - an L of two boxes, a dumbbell of two spheres on a capsule and a table
//    of five boxes, of 0.1, 1 and 10 kg, dropped 5 mm onto the ground, come
//    to rest on the face they fell on (the L flat, the dumbbell on both
//    balls, the table on its four legs) at the height that face gives;
//  - a compound falling onto another compound comes to rest on it;
//  - a cube whose explicit centre of mass lies 2 mm inside its bottom edge
//    stands, and 2 mm outside it tips over: the support polygon is the
//    cube's, the balance point the given centre of mass;
//  - a free body with a full inertia tensor (products of inertia) turns as
//    the same body described in its principal axes: the angular momentum
//    stays constant in the world and so does the kinetic energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

constexpr double kSettle = 2.0;       // s to come to rest
constexpr double kRestSpeed = 1e-3;   // m/s, fastest a resting body's point may move after kSettle
constexpr double kTilt = 0.01;        // rad, widest the resting face may tilt from level
constexpr double kHeight = 2e-3;      // m, the centre of mass's height against the face's (penetration, compliance)

ShapePart Box(const Vec3& half, const Vec3& position) {
  ShapePart p;
  p.type = ShapeType::kBox;
  p.half_extents = half;
  p.position = position;
  return p;
}

ShapePart Ball(double radius, const Vec3& position) {
  ShapePart p;
  p.type = ShapeType::kSphere;
  p.radius = radius;
  p.position = position;
  return p;
}

ShapePart Rod(double radius, double half_length, const Vec3& position, const Quat& orientation) {
  ShapePart p;
  p.type = ShapeType::kCapsule;
  p.radius = radius;
  p.half_length = half_length;
  p.position = position;
  p.orientation = orientation;
  return p;
}

// A compound and the lowest point of its parts below the frame's origin
// (m), so that the frame's origin sits that high on the ground at rest.
struct Model {
  const char* name;
  std::vector<ShapePart> parts;
  double bottom;  // m, the frame origin's height when the model rests on the ground
};

std::vector<Model> Models() {
  const Quat along_x(Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitY()));
  std::vector<Model> models;
  models.push_back({"L", {Box(Vec3(0.15, 0.03, 0.03), Vec3::Zero()), Box(Vec3(0.03, 0.12, 0.03), Vec3(0.12, 0.15, 0))},
                    0.03});
  models.push_back({"dumbbell",
                    {Ball(0.06, Vec3(-0.15, 0, 0)), Rod(0.02, 0.15, Vec3::Zero(), along_x), Ball(0.06, Vec3(0.15, 0, 0))},
                    0.06});
  std::vector<ShapePart> table = {Box(Vec3(0.2, 0.15, 0.015), Vec3(0, 0, 0.2))};
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) table.push_back(Box(Vec3(0.015, 0.015, 0.1), Vec3(0.17 * sx, 0.12 * sy, 0.085)));
  }
  models.push_back({"table", table, 0.015});
  return models;
}

BodySettings ModelSettings(const Model& m, double mass, const Vec3& at) {
  BodySettings s;
  s.shape = ShapeType::kCompound;
  s.parts = m.parts;
  s.mass = mass;
  s.restitution = 0.0;
  s.friction = 0.5;
  s.position = at;
  return s;
}

// The frame origin's world pose of body `b` (RigidBody::frame_origin).
Vec3 FrameOrigin(const RigidBody& b) { return b.x + b.q * b.frame_origin; }

double Tilt(const RigidBody& b) {
  const Vec3 up = b.q * Vec3::UnitZ();
  return std::atan2(up.cross(Vec3::UnitZ()).norm(), up.z());
}

class CompoundScenarioTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies kRestSpeed, kTilt and kHeight for each model and mass, or the
// method's refusal of compounds by its contract.
TEST_P(CompoundScenarioTest, CompoundsComeToRestOnTheirFace) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const Model& model : Models()) {
    for (const double mass : {0.1, 1.0, 10.0}) {
      testing::MethodSim sim(config.method, config.params);
      testing::AddGround(sim.world, 0.0, 0.5);
      const BodyId id = testing::AddValidBody(sim.world, ModelSettings(model, mass, Vec3(0, 0, model.bottom + 0.005)));
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) {
        return;
      }
      double speed = 0.0, reach = 0.5;  // m, no part is farther than this from the centre of mass
      const int settle = static_cast<int>(std::lround(kSettle / sim.world.dt));
      for (int i = 0; i < settle + 60; ++i) {
        sim.Step();
        const RigidBody& b = *sim.world.Find(id);
        if (i >= settle) speed = std::max(speed, b.LinearVelocity().norm() + b.AngularVelocity().norm() * reach);
      }
      const RigidBody& b = *sim.world.Find(id);
      char name[64];
      std::snprintf(name, sizeof(name), "%s %g kg", model.name, mass);
      std::printf("%-10s %-16s speed %.2e m/s, tilt %.2e rad, height %+.2e m\n", config.label.c_str(), name, speed,
                  Tilt(b), FrameOrigin(b).z() - model.bottom);
      checks.Expect(std::string(name) + " speed", speed, 0.0, kRestSpeed);
      checks.Expect(std::string(name) + " tilt", Tilt(b), 0.0, kTilt);
      checks.Expect(std::string(name) + " height", FrameOrigin(b).z(), model.bottom, kHeight);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies a table dropped onto another table comes to rest on it: compound
// against compound, the top table's legs on the lower one's top.
TEST_P(CompoundScenarioTest, TableRestsOnTable) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  testing::MethodSim sim(config.method, config.params);
  testing::AddGround(sim.world, 0.0, 0.5);
  const Model table = Models()[2];
  testing::AddValidBody(sim.world, ModelSettings(table, 2.0, Vec3(0, 0, table.bottom + 0.001)));
  // the top's upper face is 0.215 m above the frame; the legs' feet 0.015 below it
  const double rest = table.bottom + 0.215 + 0.015;
  const BodyId top = testing::AddValidBody(sim.world, ModelSettings(table, 1.0, Vec3(0.01, 0.02, rest + 0.005)));
  if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) return;
  for (int i = 0; i < static_cast<int>(std::lround(kSettle / sim.world.dt)); ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(top);
  std::printf("%-10s table on table: tilt %.2e rad, height %+.2e m\n", config.label.c_str(), Tilt(b),
              FrameOrigin(b).z() - rest);
  checks.Expect("table on table tilt", Tilt(b), 0.0, kTilt);
  checks.Expect("table on table height", FrameOrigin(b).z(), rest, 2 * kHeight);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies the balance of a cube of edge 0.2 m resting on the ground whose
// explicit centre of mass lies 0.1 m -+ 2 mm from its centre along x: inside
// the support it stands (tilt below kTilt), outside it tips (beyond 0.5 rad
// within 2 s: the fall's growth rate is sqrt(m g r / I_edge) = 7.2 /s).
TEST_P(CompoundScenarioTest, OffCentreMassTipsExactlyPastTheEdge) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double offset : {0.098, 0.102}) {
    testing::MethodSim sim(config.method, config.params);
    testing::AddGround(sim.world, 0.0, 0.8);
    BodySettings s;
    s.shape = ShapeType::kBox;
    s.half_extents = Vec3::Constant(0.1);
    s.mass = 1.0;
    s.center_of_mass = Vec3(offset, 0, 0);
    s.restitution = 0.0;
    s.friction = 0.8;
    s.position = Vec3(0, 0, 0.1);
    const BodyId id = testing::AddValidBody(sim.world, s);
    if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) {
      return;
    }
    double tilt = 0.0;
    for (int i = 0; i < static_cast<int>(std::lround(2.0 / sim.world.dt)); ++i) {
      sim.Step();
      tilt = std::max(tilt, Tilt(*sim.world.Find(id)));
    }
    std::printf("%-10s centre of mass at x = %.3f m: largest tilt %.3e rad\n", config.label.c_str(), offset, tilt);
    if (offset < 0.1) {
      checks.Expect("standing tilt", tilt, 0.0, kTilt);
    } else {
      EXPECT_GT(tilt, 0.5) << config.label;
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies torque-free rotation with products of inertia: body A carries
// I_A = R0 D R0^T at orientation identity, body B the principal D at
// orientation R0; they are one body described in two frames, so
// R_A(t) R0 = R_B(t) throughout, L stays constant in the world, and the
// kinetic energy L . w / 2 stays constant (Euler's equations conserve both).
TEST_P(CompoundScenarioTest, FullInertiaTensorTurnsAsItsPrincipalAxes) {
  const MethodConfig& config = GetParam();
  testing::MethodSim sim(config.method, config.params);
  sim.world.gravity = Vec3::Zero();
  const Quat r0(Eigen::AngleAxisd(0.8, Vec3(1, -2, 0.5).normalized()));
  const Mat3 D = Vec3(0.02, 0.03, 0.045).asDiagonal();
  const Vec3 w0(1.5, -4.0, 6.0);  // rad/s, near no principal axis
  BodySettings a;
  a.shape = ShapeType::kBox;
  a.half_extents = Vec3(0.1, 0.08, 0.05);
  a.mass = 2.0;
  a.inertia = r0.toRotationMatrix() * D * r0.toRotationMatrix().transpose();
  a.angular_velocity = w0;
  BodySettings b = a;
  b.inertia = D;
  b.orientation = Eigen::Vector4d(r0.w(), r0.x(), r0.y(), r0.z());
  b.position = Vec3(5, 0, 0);
  const BodyId ia = testing::AddValidBody(sim.world, a), ib = testing::AddValidBody(sim.world, b);
  const Vec3 L0 = sim.world.Find(ia)->L;
  const double T0 = sim.world.Find(ia)->KineticEnergy();
  ASSERT_TRUE(L0.isApprox(sim.world.Find(ib)->L, 1e-12));
  double l_drift = 0.0, t_drift = 0.0, frame_gap = 0.0;
  for (int i = 0; i < 480; ++i) {
    sim.Step();
    const RigidBody& A = *sim.world.Find(ia);
    const RigidBody& B = *sim.world.Find(ib);
    l_drift = std::max(l_drift, (A.L - L0).norm() / L0.norm());
    t_drift = std::max(t_drift, std::abs(A.KineticEnergy() - T0) / T0);
    frame_gap = std::max(frame_gap, (A.Rotation() * r0.toRotationMatrix() - B.Rotation()).norm());
  }
  std::printf("%-10s 2 s torque free: |L| drift %.2e, energy drift %.2e, frame gap %.2e\n", config.label.c_str(),
              l_drift, t_drift, frame_gap);
  EXPECT_LT(l_drift, 1e-9) << config.label;
  EXPECT_LT(t_drift, 1e-6) << config.label;
  EXPECT_LT(frame_gap, 1e-9) << config.label;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, CompoundScenarioTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
