// Kept manifolds of touching polyhedron pairs (see manifold_cache.h).
#include "service/collision/manifold_cache.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "service/collision/collide_pairs.h"
#include "service/collision/motion_bound.h"

namespace contactsim {
namespace {

bool IsPolyhedron(const RigidBody& body) {
  return body.shape.type == ShapeType::kBox || (body.shape.type == ShapeType::kConvex && body.shape.hull != nullptr);
}

}  // namespace

bool KeepsManifold(const RigidBody& a, const RigidBody& b) {
  return a.id != b.id && IsPolyhedron(a) && IsPolyhedron(b);
}

bool IsSortedByPair(const std::vector<CachedManifold>& entries) {
  // strictly increasing: sorted and no key twice
  return std::adjacent_find(entries.begin(), entries.end(), [](const CachedManifold& x, const CachedManifold& y) {
           return !(x < y);
         }) == entries.end();
}

size_t ManifoldCache::Place(BodyId a, BodyId b) const {
  // compares the ids alone: a CachedManifold key would initialise its four points on every lookup
  const auto before = [](const CachedManifold& m, const std::pair<BodyId, BodyId>& key) {
    return m.a != key.first ? m.a < key.first : m.b < key.second;
  };
  return std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(a, b), before) - entries_.begin();
}

const CachedManifold* ManifoldCache::Find(BodyId a, BodyId b) const {
  const size_t place = Place(a, b);
  const bool found = place < entries_.size() && entries_[place].a == a && entries_[place].b == b;
  return found ? &entries_[place] : nullptr;
}

void ManifoldCache::Locate(const std::vector<RigidBody>& bodies, const std::vector<std::pair<int, int>>& pairs,
                          std::vector<const CachedManifold*>* found) const {
  found->assign(pairs.size(), nullptr);
  if (entries_.empty()) return;
  size_t next = 0;  // the first entry not before the last pair's key
  std::pair<BodyId, BodyId> last(0, 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::pair<BodyId, BodyId> key(bodies[pairs[i].first].id, bodies[pairs[i].second].id);
    if (key < last) {  // the ids stopped ascending: binary searches from here on
      for (size_t k = i; k < pairs.size(); ++k) {
        (*found)[k] = Find(bodies[pairs[k].first].id, bodies[pairs[k].second].id);
      }
      return;
    }
    last = key;
    while (next < entries_.size() && std::make_pair(entries_[next].a, entries_[next].b) < key) ++next;
    if (next < entries_.size() && entries_[next].a == key.first && entries_[next].b == key.second) {
      (*found)[i] = &entries_[next];
    }
  }
}

bool ManifoldCache::ReuseAt(const CachedManifold* m, const RigidBody& a, int ia, const RigidBody& b, int ib,
                            double margin, ManifoldUpdate* update, ContactSet* out) const {
  if (m == nullptr) return false;
  // how far B's points may have moved in A's frame since the manifold was made
  const Mat3 R_A = a.Rotation();
  const Vec3 p_AB = R_A.transpose() * (b.x - a.x);
  const Quat q_AB = a.q.conjugate() * b.q;
  const double half_turn_sin = (m->q_AB.conjugate() * q_AB).vec().norm();
  const double moved = (p_AB - m->p_AB).norm() + 2.0 * half_turn_sin * m->reach_b;
  // written so that a non-finite pose is a remake
  if (!(moved <= kManifoldReuseFraction * margin)) {
    ++update->remakes;
    return false;
  }
  // the kept points at the current poses
  const Mat3 R_B = b.Rotation();
  const size_t first = out->size();
  for (int k = 0; k < m->count; ++k) {
    const CachedPoint& p = m->points[k];
    const Vec3 n = R_A * p.normal_A;
    const Vec3 on_a = a.x + R_A * p.on_a_A;
    const double depth = (on_a - (b.x + R_B * p.on_b_B)).dot(n);
    if (depth <= -margin) continue;
    AppendContact(on_a, n, depth, p.feature_id, out);
    Contact& c = out->back();
    c.a = ia;
    c.b = ib;
    c.id_a = a.id;
    c.id_b = b.id;
  }
  if (out->size() == first) {  // every point moved beyond the margin: make it again
    ++update->remakes;
    return false;
  }
  update->kind = ManifoldUpdate::Kind::kKeep;
  update->kept = static_cast<size_t>(m - entries_.data());
  ++update->reuses;
  return true;
}

void ManifoldCache::Record(const RigidBody& a, const RigidBody& b, const Contact* first, int count,
                           ManifoldUpdate* update) {
  if (count <= 0 || count > kMaxCachedPoints) return;
  CachedManifold& m = update->manifold;
  m.a = a.id;
  m.b = b.id;
  const Mat3 R_A = a.Rotation();
  const Mat3 R_B = b.Rotation();
  m.p_AB = R_A.transpose() * (b.x - a.x);
  m.q_AB = a.q.conjugate() * b.q;
  m.reach_b = BoundingRadius(b.shape);
  m.count = count;
  for (int k = 0; k < count; ++k) {
    const Contact& c = first[k];
    // the point lies midway: A's surface half the depth back along the normal, B's half forward
    const Vec3 half = 0.5 * c.depth * c.normal;
    CachedPoint& p = m.points[k];
    p.on_a_A = R_A.transpose() * (c.point + half - a.x);
    p.on_b_B = R_B.transpose() * (c.point - half - b.x);
    p.normal_A = R_A.transpose() * c.normal;
    p.feature_id = c.feature_id;
  }
  update->kind = ManifoldUpdate::Kind::kStore;
}

void ManifoldCache::Rebuild(const std::vector<ManifoldUpdate>& updates) {
  next_.clear();
  for (const ManifoldUpdate& u : updates) {
    reuses_ += u.reuses;
    remakes_ += u.remakes;
    if (u.kind == ManifoldUpdate::Kind::kKeep) next_.push_back(entries_[u.kept]);
    if (u.kind == ManifoldUpdate::Kind::kStore) next_.push_back(u.manifold);
  }
  // the broadphase's pairs come sorted by body index, which follows the ids in most worlds
  if (!std::is_sorted(next_.begin(), next_.end())) std::sort(next_.begin(), next_.end());
  entries_.swap(next_);
}

void ManifoldCache::Restore(std::vector<CachedManifold> entries) {
  if (!IsSortedByPair(entries)) {  // a programmer error: a snapshot's are checked when read
    std::fprintf(stderr, "ManifoldCache::Restore: %zu entries not sorted by (a, b)\n", entries.size());
    std::abort();
  }
  entries_ = std::move(entries);
}

void ManifoldCache::Clear() {
  entries_.clear();
  reuses_ = 0;
  remakes_ = 0;
}

}  // namespace contactsim
