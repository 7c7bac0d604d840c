// Mass ratios every method must hold: two-body stacks on the ground with
// the upper body 1, 10, 100 and 1,000 times heavier than the lower one
// (heavy on light) or lighter (light on heavy), for a box, a sphere and a
// lying capsule on a flat box; and chains of ball-jointed capsules hanging
// from the world with a heavy body at their end (heavy on light) or a light
// one (light on heavy). Each case must stay within the bounds the equal-mass
// case meets, so that a mass ratio never costs accuracy.
//
// Why these cases: an iterative solver of the contact or joint rows
// (Gauss-Seidel, projected or positional) converges at a rate of about
// 1 - m_light / m_heavy per sweep on such a stack (Erleben 2007; Catto,
// "Solver2D", 2024), so a heavy body on a light one sinks through it when
// the sweeps run out, while the equal-mass stack converges in a few.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/method_support.h"
#include "service/physics/body_settings.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddGround;
using testing::AddValidBody;
using Sim = testing::MethodSim;

constexpr double kLightMass = 0.02;  // kg, the lower box of the measured stack
constexpr double kSeconds = 2.0;     // s of simulation per case
// Bounds every case meets, the equal-mass ones with a wide margin. The
// velocity-level methods rest inside their 1 mm slop (1.0-1.1 mm deep); the
// penalty method rests at load / kp, kp from its contact time and the
// island's heaviest body (0.064 mm at 1:1000); xpbd and barrier stay at or
// outside the surface.
constexpr double kMaxPenetration = 1.5e-3;  // m, deepest overlap at any step
constexpr double kMaxSink = 1.0e-3;         // m, upper body's fall after it settled
constexpr double kMaxJointError = 1.0e-4;   // m, largest anchor separation at any step

enum class Top { kBox, kSphere, kCapsule };

const char* TopName(Top t) { return t == Top::kBox ? "box" : t == Top::kSphere ? "sphere" : "capsule"; }

// The upper body's settings with its lowest point at height z.
BodySettings UpperBody(Top top, double z) {
  BodySettings s;
  s.restitution = 0.0;
  s.friction = 0.5;
  switch (top) {
    case Top::kBox:
      s.shape = ShapeType::kBox;
      s.half_extents = Vec3(0.15, 0.15, 0.05);
      s.position = Vec3(0, 0, z + 0.05);
      break;
    case Top::kSphere:
      s.shape = ShapeType::kSphere;
      s.radius = 0.05;
      s.position = Vec3(0, 0, z + 0.05);
      break;
    case Top::kCapsule:  // lying along x
      s.shape = ShapeType::kCapsule;
      s.radius = 0.04;
      s.half_length = 0.08;
      s.position = Vec3(0, 0, z + 0.04);
      s.orientation = Eigen::Vector4d(std::sqrt(0.5), 0.0, std::sqrt(0.5), 0.0);
      break;
  }
  return s;
}

// Largest overlap (m) between any two bodies, one of them dynamic.
double Penetration(const World& world) { return std::max(0.0, -testing::SmallestGap(world)); }

// How a stack rested over `seconds`: the deepest overlap at any step, how
// far `top` sank and rose after the first eighth of the run (a stack that
// blows apart has no overlap left to measure, only its rise), and its
// sideways drift.
struct Rest {
  double penetration = 0.0, sink = 0.0, rise = 0.0, drift = 0.0;  // m
};
Rest RunStack(Sim& sim, BodyId top, double seconds = kSeconds) {
  Rest rest;
  double settled_z = 0.0, lowest_z = 1e9, highest_z = -1e9;
  const int steps = static_cast<int>(seconds / sim.world.dt);
  for (int i = 0; i < steps; ++i) {
    sim.Step();
    rest.penetration = std::max(rest.penetration, Penetration(sim.world));
    const double z = sim.world.Find(top)->x.z();
    if (i + 1 == steps / 8) settled_z = z;
    if (i + 1 >= steps / 8) lowest_z = std::min(lowest_z, z), highest_z = std::max(highest_z, z);
  }
  rest.sink = settled_z - lowest_z;
  rest.rise = highest_z - settled_z;
  rest.drift = (sim.world.Find(top)->x.head<2>()).norm();
  return rest;
}

// The bounds as checks of the suite (scenario_tolerances.h), so that a known
// miss is listed with its measurement instead of a wider bound.
void ExpectRests(testing::MechanicsChecks& checks, const std::string& id, const Rest& rest) {
  checks.Expect(id + " penetration", rest.penetration, 0.5 * kMaxPenetration, 0.5 * kMaxPenetration);
  checks.Expect(id + " sink", rest.sink, 0.5 * kMaxSink, 0.5 * kMaxSink);
  checks.Expect(id + " rise", rest.rise, 0.5 * kMaxSink, 0.5 * kMaxSink);
  checks.Expect(id + " drift", rest.drift, 0.5 * kMaxSink, 0.5 * kMaxSink);
}

using StackParam = std::tuple<std::string, Top, bool, int>;  // method, top, heavy on top, ratio

class MassRatioStackTest : public ::testing::TestWithParam<StackParam> {};

// The light body's mass and every body's friction and restitution of a
// stack case: the measured stack first, then a heavy light body on a
// slippery, bouncy pair and a lighter one on a rough, dead one (a method
// that holds one mass and material by luck fails another).
struct StackMaterial {
  double light, mu, e;
};
constexpr StackMaterial kStackMaterials[] = {{kLightMass, 0.5, 0.0}, {10.0, 0.2, 0.5}, {0.1, 0.9, 0.0}};

// Verifies that a two-body stack with the given mass ratio rests: no overlap
// deeper than kMaxPenetration at any step, and the upper body does not sink
// or rise by more than kMaxSink after the first quarter second, for each of
// kStackMaterials. Bodies start 0.1 mm apart (a barrier method pushes a
// flush start apart by hopping).
TEST_P(MassRatioStackTest, StackHolds) {
  const auto& [method, top, heavy_on_top, ratio] = GetParam();
  testing::MechanicsChecks checks(method);
  for (const StackMaterial& mat : kStackMaterials) {
    Sim sim(method);
    AddGround(sim.world, mat.e, mat.mu);
    const double gap = 1e-4;  // m
    BodySettings lower;
    lower.shape = ShapeType::kBox;
    lower.half_extents = Vec3(0.15, 0.15, 0.05);
    lower.position = Vec3(0, 0, 0.05 + gap);
    lower.restitution = mat.e;
    lower.friction = mat.mu;
    lower.mass = heavy_on_top ? mat.light : mat.light * ratio;
    AddValidBody(sim.world, lower);
    BodySettings upper = UpperBody(top, 0.1 + 2.0 * gap);
    upper.restitution = mat.e;
    upper.friction = mat.mu;
    upper.mass = heavy_on_top ? mat.light * ratio : mat.light;
    const BodyId up = AddValidBody(sim.world, upper);

    const Rest rest = RunStack(sim, up);
    std::string id = std::string(TopName(top)) + (heavy_on_top ? " heavy-on-light 1:" : " light-on-heavy 1:") +
                     std::to_string(ratio);
    if (&mat != &kStackMaterials[0]) {
      char more[48];
      std::snprintf(more, sizeof(more), " m=%g mu=%g e=%g", mat.light, mat.mu, mat.e);
      id += more;
    }
    std::printf("%-8s %s: penetration %.3g mm, sink %.3g mm, rise %.3g mm, drift %.3g mm\n", method.c_str(),
                id.c_str(), 1e3 * rest.penetration, 1e3 * rest.sink, 1e3 * rest.rise, 1e3 * rest.drift);
    ExpectRests(checks, id, rest);
  }
  SKIP_KNOWN_MISSES(checks);
}

std::string StackName(const ::testing::TestParamInfo<StackParam>& info) {
  const auto& [method, top, heavy_on_top, ratio] = info.param;
  return method + "_" + TopName(top) + (heavy_on_top ? "_HeavyOnLight_" : "_LightOnHeavy_") + std::to_string(ratio);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MassRatioStackTest,
                         ::testing::Combine(::testing::ValuesIn(ContactMethodNames()),
                                            ::testing::Values(Top::kBox, Top::kSphere, Top::kCapsule),
                                            ::testing::Bool(), ::testing::Values(1, 10, 100, 1000)),
                         StackName);

using SupportParam = std::tuple<std::string, int>;  // method, ratio

class MassRatioSupportTest : public ::testing::TestWithParam<SupportParam> {};

// A flat box of the lower stack's shape at height z (its bottom face), of
// mass m.
BodySettings FlatBox(double x, double z, double m) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3(0.15, 0.15, 0.05);
  s.position = Vec3(x, 0, z + 0.05);
  s.restitution = 0.0;
  s.friction = 0.5;
  s.mass = m;
  return s;
}

// The plank and its two supports of LightSupportsHold: a plank `ratio` times
// heavier than each of two flat boxes of mass `light` at x = -+kSupportX,
// every body of friction mu and restitution e, 0.1 mm apart.
constexpr double kSupportX = 0.35;  // m
struct Bridge {
  BodyId supports[2];
  BodyId plank;
};
Bridge AddBridge(World& world, double light, int ratio, double mu, double e) {
  const double gap = 1e-4;  // m
  Bridge bridge{};
  for (int i = 0; i < 2; ++i) {
    BodySettings s = FlatBox(i == 0 ? -kSupportX : kSupportX, gap, light);
    s.friction = mu, s.restitution = e;
    bridge.supports[i] = AddValidBody(world, s);
  }
  BodySettings plank = FlatBox(0.0, 0.1 + 2.0 * gap, light * ratio);
  plank.half_extents = Vec3(0.5, 0.15, 0.025);
  plank.position.z() = 0.1 + 2.0 * gap + 0.025;
  plank.friction = mu, plank.restitution = e;
  bridge.plank = AddValidBody(world, plank);
  return bridge;
}

// Verifies two more layouts of light supports under heavy loads, with the
// bounds of StackHolds: a plank `ratio` times heavier than each of the two
// light boxes it bridges (one component, two supports, eight contact points
// above and below), and a light box between two heavy ones (a sandwich:
// the light body's rows carry the top box's weight from above and pass it
// on below).
TEST_P(MassRatioSupportTest, LightSupportsHold) {
  const auto& [method, ratio] = GetParam();
  const double gap = 1e-4;  // m
  testing::MechanicsChecks checks(method);
  for (const bool bridge : {true, false}) {
    Sim sim(method);
    AddGround(sim.world, 0.0, 0.5);
    BodyId top = 0;
    if (bridge) {
      top = AddBridge(sim.world, kLightMass, ratio, 0.5, 0.0).plank;
    } else {
      AddValidBody(sim.world, FlatBox(0.0, gap, kLightMass * ratio));
      AddValidBody(sim.world, FlatBox(0.0, 0.1 + 2.0 * gap, kLightMass));
      top = AddValidBody(sim.world, FlatBox(0.0, 0.2 + 3.0 * gap, kLightMass * ratio));
    }
    const Rest rest = RunStack(sim, top);
    const std::string layout = bridge ? "bridge" : "sandwich";
    std::printf("%-8s %-8s 1:%-4d penetration %.3g mm, sink %.3g mm, rise %.3g mm, drift %.3g mm\n",
                method.c_str(), layout.c_str(), ratio, 1e3 * rest.penetration, 1e3 * rest.sink, 1e3 * rest.rise,
                1e3 * rest.drift);
    ExpectRests(checks, layout + " 1:" + std::to_string(ratio), rest);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies the bridge of LightSupportsHold over the light boxes' mass
// (0.1 and 10 kg), the friction (0.2 and 0.9) and the restitution (0 and
// 0.5) of every body, with the supports held too: neither may slide more
// than the top may drift. The layout is exactly symmetric, so whatever
// asymmetry a method makes grows (a soft step's supports spun out at some
// masses and not at others, and penalty's flew apart at some frictions).
class MassRatioBridgeTest : public ::testing::TestWithParam<SupportParam> {};

TEST_P(MassRatioBridgeTest, HoldsAtEveryMassAndMaterial) {
  const auto& [method, ratio] = GetParam();
  testing::MechanicsChecks checks(method);
  for (const double light : {0.1, 10.0}) {
    for (const double mu : {0.2, 0.9}) {
      for (const double e : {0.0, 0.5}) {
        Sim sim(method);
        AddGround(sim.world, e, mu);
        const Bridge bridge = AddBridge(sim.world, light, ratio, mu, e);
        const Rest rest = RunStack(sim, bridge.plank);
        double slide = 0.0;  // m, farthest a support moved sideways
        for (int i = 0; i < 2; ++i) {
          const Vec3 start(i == 0 ? -kSupportX : kSupportX, 0.0, 0.0);
          slide = std::max(slide, (sim.world.Find(bridge.supports[i])->x - start).head<2>().norm());
        }
        char id[80];
        std::snprintf(id, sizeof(id), "bridge 1:%d m=%g mu=%g e=%g", ratio, light, mu, e);
        std::printf("%-8s %s: penetration %.3g mm, sink %.3g mm, rise %.3g mm, drift %.3g mm, supports slid %.3g mm\n",
                    method.c_str(), id, 1e3 * rest.penetration, 1e3 * rest.sink, 1e3 * rest.rise, 1e3 * rest.drift,
                    1e3 * slide);
        ExpectRests(checks, id, rest);
        checks.Expect(std::string(id) + " support slide", slide, 0.5 * kMaxSink, 0.5 * kMaxSink);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies the bridge standing ten seconds at mass ratios from 3 to 300
// (restitution 0, mu 0.5, 1 kg supports): the top's drift and the
// supports' slide stay within kLongDrift, five times the most any method
// needs (barrier's supports slide 0.009 mm). A drift that grows with time
// shows only in a long run: penalty's light supports rocked in a limit
// cycle at every ratio from 3 up and walked 0.5-0.85 mm in 5-10 s, and
// xpbd's static friction dropped each step's residual slip, 0.11-0.28 mm.
constexpr double kLongDrift = 0.05e-3;  // m
class MassRatioLongBridgeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MassRatioLongBridgeTest, StandsTenSeconds) {
  const std::string& method = GetParam();
  testing::MechanicsChecks checks(method);
  for (const int ratio : {3, 30, 300}) {
    Sim sim(method);
    AddGround(sim.world, 0.0, 0.5);
    const Bridge bridge = AddBridge(sim.world, 1.0, ratio, 0.5, 0.0);
    const Rest rest = RunStack(sim, bridge.plank, 10.0);
    double slide = 0.0;  // m
    for (int i = 0; i < 2; ++i) {
      const Vec3 start(i == 0 ? -kSupportX : kSupportX, 0.0, 0.0);
      slide = std::max(slide, (sim.world.Find(bridge.supports[i])->x - start).head<2>().norm());
    }
    const std::string id = "bridge 10 s 1:" + std::to_string(ratio);
    std::printf("%-8s %s: penetration %.3g mm, sink %.3g mm, rise %.3g mm, drift %.3g mm, supports slid %.3g mm\n",
                method.c_str(), id.c_str(), 1e3 * rest.penetration, 1e3 * rest.sink, 1e3 * rest.rise,
                1e3 * rest.drift, 1e3 * slide);
    ExpectRests(checks, id, rest);
    checks.Expect(id + " walk", rest.drift, 0.5 * kLongDrift, 0.5 * kLongDrift);
    checks.Expect(id + " support slide", slide, 0.5 * kLongDrift, 0.5 * kLongDrift);
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MassRatioLongBridgeTest, ::testing::ValuesIn(ContactMethodNames()));

std::string SupportName(const ::testing::TestParamInfo<SupportParam>& info) {
  return std::get<0>(info.param) + "_" + std::to_string(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MassRatioSupportTest,
                         ::testing::Combine(::testing::ValuesIn(ContactMethodNames()),
                                            ::testing::Values(1, 100, 1000)),
                         SupportName);

INSTANTIATE_TEST_SUITE_P(EveryMethod, MassRatioBridgeTest,
                         ::testing::Combine(::testing::ValuesIn(ContactMethodNames()), ::testing::Values(100, 1000)),
                         SupportName);

using ChainParam = std::tuple<std::string, bool, int>;  // method, heavy end, ratio

class MassRatioChainTest : public ::testing::TestWithParam<ChainParam> {};

// Verifies that a chain of four light capsules (0.02 kg each) hanging from
// the world holds a box `ratio` times heavier at its end (heavy on light),
// or that four heavy links hold a light box (light on heavy): anchors
// within kMaxJointError at every step. A
// method that cannot simulate joints must say so (CheckMethodSupports).
TEST_P(MassRatioChainTest, ChainHoldsItsEnd) {
  const auto& [method, heavy_end, ratio] = GetParam();
  Sim sim(method);
  const double r = 0.02, hl = 0.05;
  const int links = 4;
  const Vec3 top(0, 0, 2.0);
  const std::vector<BodyId> chain = testing::AddHangingChain(sim.world, links, top, r, hl);
  for (BodyId id : chain) sim.world.Find(id)->SetMass(heavy_end ? kLightMass : kLightMass * ratio);
  BodySettings end;
  end.shape = ShapeType::kBox;
  end.half_extents = Vec3::Constant(0.05);
  const double tip = top.z() - links * 2.0 * (hl + r);
  end.position = Vec3(0, 0, tip - 0.05);
  end.mass = heavy_end ? kLightMass * ratio : kLightMass;
  const BodyId box = AddValidBody(sim.world, end);
  testing::AddJoint(sim.world, JointKind::kBall, box, chain.back(), Vec3(0, 0, tip));

  const Status support = CheckMethodSupports(method, sim.world);
  if (!support.ok()) {
    // refused, never silently ignored: the message names what is missing
    EXPECT_EQ(support.code(), StatusCode::kFailedPrecondition);
    EXPECT_NE(support.message().find("joints"), std::string::npos) << support.message();
    std::printf("%-8s refuses joints: %s\n", method.c_str(), support.message().c_str());
    return;
  }
  // a little swing, so that the joints carry a changing load
  sim.world.Find(box)->SetVelocity(Vec3(0.05, 0, 0), Vec3::Zero());
  double worst = 0.0;
  const int steps = static_cast<int>(kSeconds / sim.world.dt);
  for (int i = 0; i < steps; ++i) {
    sim.Step();
    worst = std::max(worst, testing::MaxAnchorSeparation(sim.world));
  }
  std::printf("%-8s chain %s 1:%-4d joint error %.3g mm\n", method.c_str(), heavy_end ? "heavy-end" : "light-end",
              ratio, 1e3 * worst);
  EXPECT_LT(worst, kMaxJointError);
  EXPECT_TRUE(std::isfinite(sim.world.Find(box)->x.norm()));
}

std::string ChainName(const ::testing::TestParamInfo<ChainParam>& info) {
  const auto& [method, heavy_end, ratio] = info.param;
  return method + (heavy_end ? "_HeavyOnLight_" : "_LightOnHeavy_") + std::to_string(ratio);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MassRatioChainTest,
                         ::testing::Combine(::testing::ValuesIn(ContactMethodNames()), ::testing::Bool(),
                                            ::testing::Values(1, 10, 100, 1000)),
                         ChainName);

}  // namespace
}  // namespace contactsim
