// The cost of one touching pair of robot links against the hull vertex
// budget (hull_vertex_budget.h, docs/models.md "Hull vertex budget"): the
// KUKA iiwa's eight link meshes (pybullet_data, 296 to 576 hull vertices
// each; the URDF's path in $CONTACTSIM_IIWA_URDF, skipped without it), each
// a compound of one hull as the model builder makes it. 64 pairs of random
// links at random orientations, each placed 1 mm into the other along a
// random direction (the deepest contact at that budget 1 mm), collided
// through the narrowphase's table; and the same pairs 2 mm apart with the
// separating-axis cache (separating_axis_cache.h), whose hits cost one axis.
// Arg: the budget (0: the full hulls).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <random>

#include "service/collision/narrowphase.h"
#include "service/model/model_file.h"
#include "service/physics/body_settings.h"
#include "service/physics/hull_vertex_budget.h"

namespace contactsim {
namespace {

constexpr int kPairs = 64;

// The iiwa's link meshes' vertices, or none without the URDF.
const std::vector<std::vector<Vec3>>& IiwaMeshes() {
  static const std::vector<std::vector<Vec3>> meshes = [] {
    std::vector<std::vector<Vec3>> out;
    const char* urdf = std::getenv("CONTACTSIM_IIWA_URDF");
    if (urdf == nullptr) return out;
    model::ModelDescription d;
    if (!model::ReadModelFile(urdf, model::ModelPaths{}, model::ReadLimits{}, &d).ok()) return out;
    for (const model::Link& l : d.links) {
      for (const model::CollisionElement& c : l.collisions) {
        if (c.geometry.type == model::GeometryType::kMesh) out.push_back(c.geometry.mesh_vertices);
      }
    }
    return out;
  }();
  return meshes;
}

RigidBody LinkBody(const std::vector<Vec3>& mesh, int budget, BodyId id, const Quat& q) {
  BodySettings s;
  s.shape = ShapeType::kCompound;
  ShapePart part;
  part.type = ShapeType::kConvex;
  if (!BudgetedHullPoints(mesh, budget, &part.points).ok()) part.points = mesh;
  s.parts.push_back(part);
  s.mass = 1.0;
  s.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  RigidBody b;
  CreateBody(s, Material{}, &b);
  b.id = id;
  return b;
}

// The body's support along u (world): the largest u . p over its hull.
double Support(const RigidBody& b, const Vec3& u) {
  const ShapeChild& child = b.shape.compound->children[0];
  const Quat q = b.q * child.orientation;
  const Vec3 x = b.x + b.q * child.position;
  double best = -1e300;
  for (const Vec3& v : child.shape.hull->vertices) best = std::max(best, u.dot(x + q * v));
  return best;
}

// The deepest contact of the pair within kSearchMargin (-kSearchMargin when
// there is none).
constexpr double kSearchMargin = 0.01;  // m
double Depth(const RigidBody& a, const RigidBody& b) {
  ContactSet contacts;
  Collide(a, 0, b, 1, kSearchMargin, &contacts);
  double depth = -kSearchMargin;
  for (const Contact& c : contacts) depth = std::max(depth, c.depth);
  return depth;
}

// Moves B (centred on A) along u until the pair's deepest contact is
// `depth` (m; negative: a gap), by bisection: the depth only falls as B
// moves out along a fixed direction, as both are convex.
void PlaceAtDepth(const RigidBody& a, const Vec3& u, double depth, RigidBody* b) {
  const Vec3 start = b->x;
  double in = 0.0, out = Support(a, u) + Support(*b, -u) + kSearchMargin;
  for (int k = 0; k < 50; ++k) {
    const double mid = 0.5 * (in + out);
    b->x = start + mid * u;
    (Depth(a, *b) > depth ? in : out) = mid;
  }
  b->x = start + in * u;
}

// kPairs random pairs of links, B moved along u until the two overlap by
// `overlap` (m; negative: a gap).
std::vector<std::pair<RigidBody, RigidBody>> Pairs(int budget, double overlap) {
  const auto& meshes = IiwaMeshes();
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(meshes.size()) - 1);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<std::pair<RigidBody, RigidBody>> out;
  for (int k = 0; k < kPairs; ++k) {
    const int i = pick(rng), j = pick(rng);
    const Quat qa = Quat(Eigen::Vector4d{n(rng), n(rng), n(rng), n(rng)}).normalized();
    const Quat qb = Quat(Eigen::Vector4d{n(rng), n(rng), n(rng), n(rng)}).normalized();
    const Vec3 u = Vec3{n(rng), n(rng), n(rng)}.normalized();
    // ids of their own, so that each pair has its own cache entry
    RigidBody a = LinkBody(meshes[i], budget, 2 * k + 1, qa);
    RigidBody b = LinkBody(meshes[j], budget, 2 * k + 2, qb);
    PlaceAtDepth(a, u, overlap, &b);
    out.emplace_back(std::move(a), std::move(b));
  }
  return out;
}

constexpr char kNoIiwa[] = "set CONTACTSIM_IIWA_URDF to pybullet_data's kuka_iiwa/model.urdf";

// Collides every pair once per iteration (through the narrowphase's cache
// when one is given) and reports the time per pair and the contacts found.
void CollideEveryPair(benchmark::State& state, const std::vector<std::pair<RigidBody, RigidBody>>& pairs,
                      Narrowphase* cached) {
  ContactSet contacts;
  int64_t tests = 0, found = 0;
  for (auto _ : state) {
    for (const auto& [a, b] : pairs) {
      contacts.clear();
      found += cached != nullptr ? cached->Collide(a, 0, b, 1, 0.0, &contacts) : Collide(a, 0, b, 1, 0.0, &contacts);
    }
    tests += static_cast<int64_t>(pairs.size());
  }
  state.counters["per_pair"] =
      benchmark::Counter(static_cast<double>(tests), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["contacts_per_pair"] = static_cast<double>(found) / static_cast<double>(std::max<int64_t>(1, tests));
}

void BM_TouchingIiwaLinks(benchmark::State& state) {
  if (IiwaMeshes().empty()) return state.SkipWithError(kNoIiwa);
  CollideEveryPair(state, Pairs(static_cast<int>(state.range(0)), 1e-3), nullptr);
}
BENCHMARK(BM_TouchingIiwaLinks)->Arg(0)->Arg(128)->Arg(64)->Arg(32)->Arg(16)->Unit(benchmark::kMicrosecond);

void BM_NearIiwaLinksCached(benchmark::State& state) {
  if (IiwaMeshes().empty()) return state.SkipWithError(kNoIiwa);
  const bool cached = state.range(1) == 1;
  Narrowphase narrowphase;
  CollideEveryPair(state, Pairs(static_cast<int>(state.range(0)), -2e-3), cached ? &narrowphase : nullptr);
  state.SetLabel(cached ? "with cache" : "without cache");
}
BENCHMARK(BM_NearIiwaLinksCached)->Args({0, 0})->Args({0, 1})->Args({64, 0})->Args({64, 1});

}  // namespace
}  // namespace contactsim
