// Tests of xpbd's overlaps present at a step's start (AllowXpbdStartOverlaps,
// xpbd_contact.h; docs/methods/xpbd.md, "Overlaps found at a step's start"):
// bodies placed overlapping leave their overlaps in position, slowly and
// without speed, at every mass and size, while a body landing on them is
// stopped at once, and a run continued from the method's saved state goes
// on bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/contact/xpbd/xpbd_method.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using Sim = testing::MethodSim;

// The placement suite's "visible" speed (placement_contact_test.cpp).
constexpr double kMaxSpeed = 1e-2;  // m/s

// A cube of half size `half` and mass `mass` at `p`, mu 0.5, e = 0.
BodyId AddCube(World& world, double half, double mass, const Vec3& p, const Vec3& v = Vec3::Zero()) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3::Constant(half);
  s.position = p;
  s.linear_velocity = v;
  s.mass = mass;
  s.friction = 0.5;
  s.restitution = 0.0;
  return testing::AddValidBody(world, s);
}

// `count` cubes stacked on the ground, each contact `overlap` deep.
void BuildStack(World& world, int count, double half, double mass, double overlap) {
  testing::AddGround(world, 0.0, 0.5);
  for (int i = 0; i < count; ++i) AddCube(world, half, mass, Vec3(0, 0, half * (1 + 2 * i) - overlap * (i + 1)));
}

// The fastest point of any dynamic body (|v| + |w| reach) and the deepest
// reported contact, now.
double FastestPoint(const World& world) {
  double fastest = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (!b.IsDynamic()) continue;
    const double reach = b.shape.half_extents.norm();
    fastest = std::max(fastest, b.LinearVelocity().norm() + b.AngularVelocity().norm() * reach);
  }
  return fastest;
}

double Deepest(const ContactSet& contacts) {
  double deepest = 0.0;
  for (const Contact& c : contacts) deepest = std::max(deepest, c.depth);
  return deepest;
}

// Verifies that one cube and stacks of three placed 0.1 and 0.5 mm into
// each other and the ground, at 0.1, 1 and 10 kg and 0.04, 0.1 and 0.3 m,
// never move faster than 1 cm/s and have their overlaps gone (below
// 0.01 mm) within 0.5 s: start_overlap_velocity (2 mm/s) or
// start_overlap_time (0.25 s), whichever is faster, takes 0.25 s for 0.5 mm.
TEST(XpbdStartOverlap, PlacedOverlapsLeaveSlowlyAtEveryMassAndSize) {
  for (const int count : {1, 3}) {
    for (const double half : {0.02, 0.05, 0.15}) {
      for (const double mass : {0.1, 1.0, 10.0}) {
        for (const double overlap : {1e-4, 5e-4}) {
          Sim sim("xpbd");
          BuildStack(sim.world, count, half, mass, overlap);
          double fastest = 0.0, deepest_late = 0.0;
          while (sim.world.time < 1.0 - 1e-9) {
            sim.Step();
            fastest = std::max(fastest, FastestPoint(sim.world));
            if (sim.world.time > 0.5) deepest_late = std::max(deepest_late, Deepest(sim.contacts));
          }
          std::printf("xpbd start overlap: %d cube(s) half %g m %g kg overlap %g mm: fastest %.3g m/s, deepest "
                      "after 0.5 s %.3g mm\n",
                      count, half, mass, overlap * 1e3, fastest, deepest_late * 1e3);
          EXPECT_LT(fastest, kMaxSpeed) << count << " cubes, half " << half << ", " << mass << " kg, " << overlap;
          EXPECT_LT(deepest_late, 1e-5) << count << " cubes, half " << half << ", " << mass << " kg, " << overlap;
        }
      }
    }
  }
}

// Verifies that a cube landing at 1 m/s on a stack of three placed 0.5 mm
// deep is stopped by its new contact at once, at every mass: the landing
// contact is no start overlap, so its depth is pushed out within the step
// after it is found (below 0.5 mm of overlap at any time), and the stack
// under it stays below 5 cm/s after the landing's 0.1 s.
TEST(XpbdStartOverlap, LandingOnAnOverlappingStackActsInFull) {
  const double half = 0.05, overlap = 5e-4;
  for (const double mass : {0.1, 1.0, 10.0}) {
    Sim sim("xpbd");
    BuildStack(sim.world, 3, half, 1.0, overlap);
    AddCube(sim.world, half, mass, Vec3(0, 0, 7 * half + 0.01), Vec3(0, 0, -1.0));
    double deepest_new = 0.0, fastest_late = 0.0;
    const BodyId top = sim.world.bodies().back().id;
    while (sim.world.time < 1.0 - 1e-9) {
      sim.Step();
      for (const Contact& c : sim.contacts) {
        if (sim.world.bodies()[c.b].id == top || sim.world.bodies()[c.a].id == top) {
          deepest_new = std::max(deepest_new, c.depth);
        }
      }
      if (sim.world.time > 0.1) fastest_late = std::max(fastest_late, FastestPoint(sim.world));
    }
    const double z = sim.world.Find(top)->x.z();
    std::printf("xpbd landing %g kg on a placed stack: deepest new contact %.3g mm, fastest after 0.1 s %.3g m/s, "
                "height %.5f m\n",
                mass, deepest_new * 1e3, fastest_late, z);
    EXPECT_LT(deepest_new, overlap) << mass << " kg";
    EXPECT_LT(fastest_late, 5 * kMaxSpeed) << mass << " kg";
    EXPECT_NEAR(z, 7 * half, 4 * overlap) << mass << " kg";
  }
}

// Verifies that the overlaps still allowed travel with the method's state:
// a placed stack run 0.1 s, its world, method state and the detector's kept
// manifolds (manifold_cache.h) copied into a new method and detector, and
// both run on for 0.2 s end on the same poses bit for bit (the
// snapshot suite checks every method's exact continuation on its own scene).
TEST(XpbdStartOverlap, SavedStateContinuesThePushOutExactly) {
  Sim sim("xpbd");
  BuildStack(sim.world, 3, 0.05, 1.0, 5e-4);
  while (sim.world.time < 0.1 - 1e-9) sim.Step();
  Sim copy("xpbd");
  copy.world = sim.world;
  const std::string state = sim.method->SaveState();
  ASSERT_FALSE(state.empty());
  ASSERT_TRUE(copy.method->LoadState(state).ok());
  copy.detector.RestoreManifolds(sim.detector.manifolds().entries());
  for (int i = 0; i < 48; ++i) {
    sim.Step();
    copy.Step();
  }
  for (size_t i = 0; i < sim.world.bodies().size(); ++i) {
    EXPECT_EQ(sim.world.bodies()[i].x, copy.world.bodies()[i].x) << "body " << i;
    EXPECT_EQ(sim.world.bodies()[i].q.coeffs(), copy.world.bodies()[i].q.coeffs()) << "body " << i;
  }
  // a state cut short is refused
  XpbdMethod fresh;
  EXPECT_FALSE(fresh.LoadState(state.substr(0, state.size() - 1)).ok());
}

}  // namespace
}  // namespace contactsim
