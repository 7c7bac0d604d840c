// Narrowphase time with and without the separating-axis cache (Baraff 1989:
// keep the axis that separated a pair last step and test it first) on 1,000
// falling boxes: a 10 x 10 x 10 lattice, spacing 0.3 m, half extent 0.1 m,
// random orientations and spins (fixed seed), so neighbours' bounding boxes
// overlap while the boxes themselves stay apart. The trajectory of poses is
// recorded once; each benchmark iteration replays it, so both variants see
// exactly the same pairs. A hit costs one axis tested on the bodies' own
// frames (separating_axis_cache.h); only a miss poses the two polyhedra.
#include <benchmark/benchmark.h>

#include <random>

#include "service/collision/broadphase.h"
#include "service/collision/narrowphase.h"
#include "service/physics/body_settings.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

constexpr int kFrames = 60;  // 0.25 s at dt = 1/240

struct Trajectory {
  std::vector<std::vector<RigidBody>> frames;
  std::vector<std::vector<BodyPair>> pairs;
};

const Trajectory& FallingBoxes() {
  static const Trajectory traj = [] {
    World world;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 10; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 10; ++i) {
          BodySettings s;
          s.shape = ShapeType::kBox;
          s.half_extents = Vec3::Constant(0.1);
          s.position = Vec3(0.3 * i, 0.3 * j, 0.5 + 0.3 * k);
          s.orientation = Eigen::Vector4d{u(rng), u(rng), u(rng), u(rng)};
          s.angular_velocity = Vec3{u(rng), u(rng), u(rng)};
          RigidBody b;
          CreateBody(s, Material{}, &b);
          world.AddBody(b);
        }
    Trajectory t;
    std::unique_ptr<Broadphase> bp;
    CreateBroadphase("sap", &bp);
    std::vector<Aabb> boxes(world.bodies().size());
    std::vector<bool> movable(world.bodies().size(), true);
    for (int f = 0; f < kFrames; ++f) {
      for (size_t i = 0; i < boxes.size(); ++i) boxes[i] = ComputeAabb(world.bodies()[i], 0.0, world.dt);
      std::vector<BodyPair> pairs;
      bp->FindPairs(boxes, movable, &pairs);
      t.frames.push_back(world.bodies());
      t.pairs.push_back(pairs);
      world.AccumulateForces();
      for (RigidBody& b : world.bodies()) AdvanceBallistic(b, world.dt);
    }
    return t;
  }();
  return traj;
}

void BM_NarrowphaseFallingBoxes(benchmark::State& state) {
  const bool cached = state.range(0) == 1;
  const Trajectory& t = FallingBoxes();
  Narrowphase narrowphase;
  ContactSet contacts;
  int64_t pair_tests = 0;
  for (auto _ : state) {
    // every replay starts cold, as a new scene would, so the hit rate is that
    // of one 60-step run whatever the iteration count
    narrowphase.Reset();
    for (size_t f = 0; f < t.frames.size(); ++f) {
      const auto& bodies = t.frames[f];
      contacts.clear();
      for (const BodyPair& p : t.pairs[f]) {
        if (cached) {
          narrowphase.Collide(bodies[p.first], p.first, bodies[p.second], p.second, 0.0, &contacts);
        } else {
          Collide(bodies[p.first], p.first, bodies[p.second], p.second, 0.0, &contacts);
        }
      }
      pair_tests += static_cast<int64_t>(t.pairs[f].size());
      benchmark::DoNotOptimize(contacts.data());
    }
  }
  state.counters["pairs_per_frame"] = static_cast<double>(t.pairs[0].size());
  state.counters["ns_per_pair"] =
      benchmark::Counter(static_cast<double>(pair_tests), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  if (cached) {
    const auto& c = narrowphase.cache();
    state.counters["hit_rate"] = static_cast<double>(c.hits()) / std::max<int64_t>(1, c.hits() + c.misses());
  }
  state.SetLabel(cached ? "with cache" : "without cache");
}
BENCHMARK(BM_NarrowphaseFallingBoxes)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace contactsim
