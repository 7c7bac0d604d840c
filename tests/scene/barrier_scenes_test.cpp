// Tests of the barrier method's guarantee on the standard scenes
// (config/scenes, issue 8): no two bodies touch at any step. The scenes are
// loaded by the scene loader; the 1,000-body sphere pile is cut to a block
// of its bodies (the walls and the ground kept) and runs for fewer steps than
// its benchmark length, so that the test stays within a second: the barrier
// method's candidate search is all pairs (O(n^2)).
// Not here yet, because the guarantee does not hold on them: box_rain cut
// to a 2 x 2 x 3 block starts with two boxes overlapping by 7.5 mm (the
// scene's random orientations on a 0.3 m lattice; an unsigned-distance
// barrier cannot see, let alone undo, an overlap) and takes 60 s for 192
// steps; the middle of box_pyramid (placed exactly touching, parted from a
// shifted zero) shows a narrowphase gap of -0.69 mm within 120 steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/contact/barrier/barrier_method.h"
#include "service/scene/scene_spec.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

World LoadScene(const std::string& name) {
  SceneSpec spec;
  World world;
  const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + name + ".pbtxt";
  Status st = LoadSceneFile(path, &spec);
  EXPECT_TRUE(st.ok()) << st.message();
  st = BuildWorld(spec, &world);
  EXPECT_TRUE(st.ok()) << st.message();
  return world;
}

// Removes the dynamic bodies `keep` rejects; static bodies all stay.
void Reduce(World* world, const std::function<bool(const RigidBody&)>& keep) {
  std::vector<BodyId> drop;
  for (const RigidBody& b : world->bodies()) {
    if (b.IsDynamic() && !keep(b)) drop.push_back(b.id);
  }
  for (BodyId id : drop) EXPECT_TRUE(world->RemoveBody(id).ok());
}

using testing::SmallestGap;
struct Outcome {
  double smallest_gap = std::numeric_limits<double>::infinity();  // m, narrowphase, every step
  double smallest_barrier = std::numeric_limits<double>::infinity();  // m, the method's own (StepStats residual)
  int most_iterations = 0;
  double largest_kappa = 0.0;  // N/m
  int unconverged = 0;
};

Outcome RunBarrier(World& world, int steps) {
  BarrierMethod method;
  CollisionDetector detector;
  ContactSet contacts;
  Outcome out;
  for (int i = 0; i < steps; ++i) {
    const StepStats stats = method.Step(world, detector, &contacts);
    out.smallest_gap = std::min(out.smallest_gap, SmallestGap(world));
    out.smallest_barrier = std::min(out.smallest_barrier, stats.residual);
    out.most_iterations = std::max(out.most_iterations, stats.iterations);
    out.largest_kappa = std::max(out.largest_kappa, method.barrier_stiffness());
    out.unconverged += stats.substeps == 0;
  }
  return out;
}

void Report(const char* scene, size_t bodies, int steps, const Outcome& o) {
  std::printf("barrier %s (%zu bodies, %d steps): smallest gap %.3g m (barrier %.3g m), at most %d Newton "
              "iterations, %d unconverged steps, kappa up to %.3g N/m\n",
              scene, bodies, steps, o.smallest_gap, o.smallest_barrier, o.most_iterations, o.unconverged,
              o.largest_kappa);
}

// Verifies the guarantee on `bounce`, whole: the ball falls 0.9 m, bounces
// and settles without ever touching the ground.
TEST(BarrierScenes, BounceNeverTouches) {
  World world = LoadScene("bounce");
  const Outcome o = RunBarrier(world, 480);
  Report("bounce", world.bodies().size(), 480, o);
  EXPECT_GT(o.smallest_gap, 0.0);
  EXPECT_GT(o.smallest_barrier, 0.0);
}

// Verifies the guarantee on `sphere_pile` cut to the 2 x 2 columns nearest
// the centre and the lowest four layers (16 spheres, walls and ground), for
// 1 s: they land on the ground and on each other.
TEST(BarrierScenes, SpherePileBlockNeverTouches) {
  World world = LoadScene("sphere_pile");
  Reduce(&world, [](const RigidBody& b) { return std::abs(b.x.x()) < 0.2 && std::abs(b.x.y()) < 0.2 && b.x.z() < 1.3; });
  const Outcome o = RunBarrier(world, 240);
  Report("sphere_pile block", world.bodies().size(), 240, o);
  EXPECT_GT(o.smallest_gap, 0.0);
  EXPECT_GT(o.smallest_barrier, 0.0);
}

}  // namespace
}  // namespace contactsim
