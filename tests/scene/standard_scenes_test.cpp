// Tests of the four standard benchmark scenes (config/scenes):
// each loads, builds, and has the bodies, steps and layout the issue states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "service/collision/narrowphase.h"
#include "service/scene/scene_spec.h"

namespace contactsim {
namespace {

constexpr double kDt = 1.0 / 240.0;  // s
constexpr double kTight = 1e-12;     // m, exact decimal layouts

struct Loaded {
  SceneSpec spec;
  World world;
};

Loaded Load(const char* name) {
  Loaded l;
  const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + name;
  const Status st = LoadSceneFile(path, &l.spec);
  EXPECT_TRUE(st.ok()) << st.message();
  const Status built = BuildWorld(l.spec, &l.world);
  EXPECT_TRUE(built.ok()) << built.message();
  return l;
}

int Count(const World& w, ShapeType type, bool dynamic) {
  int n = 0;
  for (const RigidBody& b : w.bodies()) n += b.shape.type == type && b.IsDynamic() == dynamic;
  return n;
}

const RigidBody* Named(const World& w, const std::string& name) {
  for (const RigidBody& b : w.bodies()) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

// Common to all: z up, g = 9.81, dt = 1/240 s, friction 0.5, density 1000.
void ExpectCommon(const Loaded& l, int steps) {
  EXPECT_EQ(l.spec.steps, steps);
  EXPECT_NEAR(l.world.dt, kDt, 1e-15);
  EXPECT_EQ(l.world.gravity, Vec3(0, 0, -9.81));
  EXPECT_EQ(Count(l.world, ShapeType::kPlane, false), 1);
  for (const RigidBody& b : l.world.bodies()) {
    EXPECT_EQ(b.material.friction, 0.5) << b.name;
  }
}

// Inner faces of the four walls at +-inner (m), 0.2 m thick, 4 m tall.
void ExpectWalls(const World& w, double inner) {
  ASSERT_EQ(Count(w, ShapeType::kBox, false), 4);
  for (const RigidBody& b : w.bodies()) {
    if (b.shape.type != ShapeType::kBox || b.IsDynamic()) continue;
    const Vec3& h = b.shape.half_extents;
    const int axis = h.x() < h.y() ? 0 : 1;
    EXPECT_NEAR(2.0 * h[axis], 0.2, kTight) << b.name;
    EXPECT_NEAR(2.0 * h.z(), 4.0, kTight) << b.name;
    EXPECT_NEAR(b.x.z() - h.z(), 0.0, kTight) << b.name;
    EXPECT_NEAR(std::abs(b.x[axis]) - h[axis], inner, kTight) << b.name;
    EXPECT_GE(h[1 - axis], inner + 0.2) << b.name << " leaves a gap at the corner";
  }
}

// Verifies sphere_pile: 1,000 spheres r = 0.1 m of 1000 kg/m^3 in a
// 10 x 10 x 10 lattice from z = 0.5 m, jittered by at most 0.01 m in x and
// y only, inside walls at +-1.5 m, restitution 0.
TEST(StandardScenes, SpherePile) {
  const Loaded l = Load("sphere_pile.pbtxt");
  ExpectCommon(l, 2400);
  EXPECT_EQ(l.world.bodies().size(), 1005u);
  EXPECT_EQ(Count(l.world, ShapeType::kSphere, true), 1000);
  ExpectWalls(l.world, 1.5);
  double lowest = 1e9;
  for (const RigidBody& b : l.world.bodies()) {
    if (!b.IsDynamic()) continue;
    EXPECT_EQ(b.shape.radius, 0.1);
    EXPECT_NEAR(b.mass, 1000.0 * 4.0 / 3.0 * M_PI * 1e-3, 1e-9);
    EXPECT_EQ(b.material.restitution, 0.0);
    const double i = std::round((b.x.x() + 1.125) / 0.25), j = std::round((b.x.y() + 1.125) / 0.25);
    EXPECT_LE(std::abs(b.x.x() - (-1.125 + 0.25 * i)), 0.01 + kTight);
    EXPECT_LE(std::abs(b.x.y() - (-1.125 + 0.25 * j)), 0.01 + kTight);
    const double k = (b.x.z() - 0.5) / 0.25;
    EXPECT_NEAR(k, std::round(k), 1e-9);
    lowest = std::min(lowest, b.x.z());
    EXPECT_LT(std::abs(b.x.x()) + 0.1, 1.5);
    EXPECT_LT(std::abs(b.x.y()) + 0.1, 1.5);
  }
  EXPECT_EQ(lowest, 0.5);
}

// Verifies box_pyramid: 210 unit cubes in rows of 20, 19, ..., 1 offset by
// 0.5 m, the base resting on the plane, every box touching, the top one
// named "top" at z = 19.5 m.
TEST(StandardScenes, BoxPyramid) {
  const Loaded l = Load("box_pyramid.pbtxt");
  ExpectCommon(l, 2400);
  EXPECT_EQ(l.world.bodies().size(), 211u);
  EXPECT_EQ(Count(l.world, ShapeType::kBox, true), 210);
  int per_row[20] = {};
  for (const RigidBody& b : l.world.bodies()) {
    if (!b.IsDynamic()) continue;
    EXPECT_EQ(b.shape.half_extents, Vec3::Constant(0.5));
    EXPECT_NEAR(b.mass, 1000.0, 1e-9);
    EXPECT_EQ(b.x.y(), 0.0);
    const int row = static_cast<int>(std::round(b.x.z() - 0.5));
    ASSERT_GE(row, 0);
    ASSERT_LT(row, 20);
    EXPECT_EQ(b.x.z(), 0.5 + row);
    const double slot = b.x.x() - (-9.5 + 0.5 * row);  // 0, 1, ..., 19 - row
    EXPECT_EQ(slot, std::round(slot));
    EXPECT_GE(slot, 0.0);
    EXPECT_LE(slot, 19.0 - row);
    ++per_row[row];
  }
  for (int r = 0; r < 20; ++r) EXPECT_EQ(per_row[r], 20 - r) << "row " << r;
  const RigidBody* top = Named(l.world, "top");
  ASSERT_NE(top, nullptr);
  EXPECT_EQ(top->x, Vec3(0, 0, 19.5));
}

// Verifies box_rain: 1,000 boxes of half extent 0.1 m in a 10 x 10 x 10
// lattice of spacing 0.3 m from z = 0.5 m, random unit orientations (not
// all the same), inside walls at +-1.6 m that no box touches at the start,
// and no two boxes overlapping (orientations are redrawn until clear: at
// 0.3 m spacing two boxes reaching 0.173 m from their centres could).
TEST(StandardScenes, BoxRain) {
  const Loaded l = Load("box_rain.pbtxt");
  ExpectCommon(l, 2400);
  EXPECT_EQ(l.world.bodies().size(), 1005u);
  EXPECT_EQ(Count(l.world, ShapeType::kBox, true), 1000);
  ExpectWalls(l.world, 1.6);
  int identity = 0;
  double lowest = 1e9;
  for (const RigidBody& b : l.world.bodies()) {
    if (!b.IsDynamic()) continue;
    EXPECT_EQ(b.shape.half_extents, Vec3::Constant(0.1));
    EXPECT_NEAR(b.mass, 8.0, 1e-9);
    EXPECT_NEAR(b.q.norm(), 1.0, 1e-12);
    identity += b.q.isApprox(Quat::Identity(), 1e-6);
    // farthest corner of a rotated box from its centre: 0.1 sqrt(3) m
    const Vec3 reach = (b.Rotation().cwiseAbs() * Vec3::Constant(0.1));
    EXPECT_LT(std::abs(b.x.x()) + reach.x(), 1.6);
    EXPECT_LT(std::abs(b.x.y()) + reach.y(), 1.6);
    EXPECT_GT(b.x.z() - reach.z(), 0.0);
    lowest = std::min(lowest, b.x.z());
  }
  EXPECT_EQ(identity, 0);
  EXPECT_EQ(lowest, 0.5);
  const auto& bodies = l.world.bodies();
  int overlapping = 0, close = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    for (size_t j = i + 1; j < bodies.size(); ++j) {
      if (!bodies[i].IsDynamic() || !bodies[j].IsDynamic()) continue;
      if ((bodies[i].x - bodies[j].x).norm() > 0.35) continue;  // two half-diagonals apart
      const double gap = PairSignedDistance(bodies[i], bodies[j], 1.0);
      overlapping += gap <= 0.0;
      close += gap < 0.01;
    }
  }
  EXPECT_EQ(overlapping, 0);
  EXPECT_GT(close, 0);  // orientations still random: some corners come close
}

// Verifies bounce: one sphere "ball" of radius 0.1 m whose lowest point is
// 0.9 m above the plane, at rest, restitution 0.5 on both surfaces.
TEST(StandardScenes, Bounce) {
  const Loaded l = Load("bounce.pbtxt");
  ExpectCommon(l, 480);
  ASSERT_EQ(l.world.bodies().size(), 2u);
  const RigidBody* ball = Named(l.world, "ball");
  ASSERT_NE(ball, nullptr);
  EXPECT_EQ(ball->shape.type, ShapeType::kSphere);
  EXPECT_NEAR(ball->x.z() - ball->shape.radius, 0.9, kTight);
  EXPECT_EQ(ball->LinearVelocity(), Vec3::Zero());
  for (const RigidBody& b : l.world.bodies()) EXPECT_EQ(b.material.restitution, 0.5) << b.name;
}

}  // namespace
}  // namespace contactsim
