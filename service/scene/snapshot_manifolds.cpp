#include "service/scene/snapshot_manifolds.h"

#include <cmath>
#include <string>
#include <utility>

namespace contactsim {
namespace {

using google::protobuf::RepeatedField;

void PutVec3(const Vec3& v, RepeatedField<double>* out) {
  for (int k = 0; k < 3; ++k) out->Add(v[k]);
}

// Exactly three finite numbers, or a message naming the field.
Status GetVec3(const RepeatedField<double>& in, const std::string& field, Vec3* v) {
  if (in.size() != 3) return Status::InvalidArgument(field + " must hold 3 numbers, got " + std::to_string(in.size()));
  for (int k = 0; k < 3; ++k) (*v)[k] = in.Get(k);
  if (!v->allFinite()) return Status::InvalidArgument(field + " must be finite");
  return Status::Ok();
}

Status LoadManifoldPoint(const proto::SnapshotManifold::Point& in, const std::string& where, CachedPoint* p) {
  Status st = GetVec3(in.on_a(), where + "on_a", &p->on_a_A);
  if (st.ok()) st = GetVec3(in.on_b(), where + "on_b", &p->on_b_B);
  if (st.ok()) st = GetVec3(in.normal(), where + "normal", &p->normal_A);
  p->feature_id = in.feature_id();
  return st;
}

Status LoadManifold(const proto::SnapshotManifold& in, CachedManifold* m) {
  const std::string where = "manifold (" + std::to_string(in.body_a()) + ", " + std::to_string(in.body_b()) + ") ";
  m->a = in.body_a();
  m->b = in.body_b();
  Status st = GetVec3(in.p_ab(), where + "p_ab", &m->p_AB);
  if (!st.ok()) return st;
  if (in.q_ab_size() != 4) return Status::InvalidArgument(where + "q_ab must hold 4 numbers, got " +
                                                          std::to_string(in.q_ab_size()));
  m->q_AB = Quat(in.q_ab(0), in.q_ab(1), in.q_ab(2), in.q_ab(3));
  if (!m->q_AB.coeffs().allFinite()) return Status::InvalidArgument(where + "q_ab must be finite");
  m->reach_b = in.reach_b();
  if (!(std::isfinite(m->reach_b) && m->reach_b >= 0.0)) {
    return Status::InvalidArgument(where + "reach_b must be finite and >= 0, got " + std::to_string(m->reach_b));
  }
  if (in.points_size() < 1 || in.points_size() > kMaxCachedPoints) {
    return Status::InvalidArgument(where + "must hold 1 to " + std::to_string(kMaxCachedPoints) + " points, got " +
                                   std::to_string(in.points_size()));
  }
  m->count = in.points_size();
  for (int k = 0; k < m->count; ++k) {
    st = LoadManifoldPoint(in.points(k), where + "point " + std::to_string(k) + " ", &m->points[k]);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

}  // namespace

void SaveManifolds(const ManifoldCache& cache, proto::Snapshot* out) {
  for (const CachedManifold& m : cache.entries()) {
    proto::SnapshotManifold* p = out->add_manifolds();
    p->set_body_a(m.a);
    p->set_body_b(m.b);
    PutVec3(m.p_AB, p->mutable_p_ab());
    for (double c : {m.q_AB.w(), m.q_AB.x(), m.q_AB.y(), m.q_AB.z()}) p->add_q_ab(c);
    p->set_reach_b(m.reach_b);
    for (int k = 0; k < m.count; ++k) {
      proto::SnapshotManifold::Point* q = p->add_points();
      PutVec3(m.points[k].on_a_A, q->mutable_on_a());
      PutVec3(m.points[k].on_b_B, q->mutable_on_b());
      PutVec3(m.points[k].normal_A, q->mutable_normal());
      q->set_feature_id(m.points[k].feature_id);
    }
  }
}

Status ReadManifolds(const proto::Snapshot& snap, std::vector<CachedManifold>* out) {
  std::vector<CachedManifold> entries(snap.manifolds_size());
  for (int i = 0; i < snap.manifolds_size(); ++i) {
    const Status st = LoadManifold(snap.manifolds(i), &entries[i]);
    if (!st.ok()) return Status::InvalidArgument("snapshot: " + st.message());
  }
  if (!IsSortedByPair(entries)) {
    return Status::InvalidArgument("snapshot: manifolds must be in ascending (body_a, body_b) order, each pair once");
  }
  *out = std::move(entries);
  return Status::Ok();
}

}  // namespace contactsim
