#include "service/contact/penalty/penalty_friction.h"

#include <algorithm>

namespace contactsim {

bool FrictionAnchors::Find(const Contact& c, AnchorState* state) const {
  const auto it = current_.find(MakeKey(c));
  if (it == current_.end()) return false;
  *state = it->second;
  // stored for the pair in id order: B relative to A flips with the order
  if (c.id_a > c.id_b) state->stretch = -state->stretch;
  return true;
}

void FrictionAnchors::Keep(const Contact& c, const AnchorState& state) {
  AnchorState s = state;
  if (c.id_a > c.id_b) s.stretch = -s.stretch;
  next_[MakeKey(c)] = s;
}

bool FrictionAnchors::PairRestDepth(BodyId a, BodyId b, double* rest) const {
  const BodyId lo = std::min(a, b), hi = std::max(a, b);
  int points = 0;
  double largest = 0.0, sum = 0.0;
  for (auto it = current_.lower_bound(Key{lo, hi, 0});
       it != current_.end() && std::get<0>(it->first) == lo && std::get<1>(it->first) == hi; ++it) {
    const double r = it->second.rest_depth;
    largest = points == 0 ? r : std::max(largest, r);
    sum += r;
    ++points;
  }
  if (points == 0) return false;
  *rest = largest >= 0.0 ? largest : sum / points;
  return true;
}

void FrictionAnchors::Commit() {
  current_.swap(next_);
  next_.clear();
}

void FrictionAnchors::Clear() {
  current_.clear();
  next_.clear();
}

void FrictionAnchors::Save(ByteWriter* out) const {
  out->Put(static_cast<uint64_t>(current_.size()));
  for (const auto& [key, s] : current_) {
    out->Put(std::get<0>(key));
    out->Put(std::get<1>(key));
    out->Put(std::get<2>(key));
    out->PutVec3(s.stretch);
    out->Put(static_cast<uint8_t>(s.penetrating));
    out->Put(s.impact_speed);
    out->Put(s.rest_depth);
  }
}

bool FrictionAnchors::Load(ByteReader* in) {
  uint64_t n = 0;
  if (!in->Get(&n)) return false;
  std::map<Key, AnchorState> loaded;
  for (uint64_t i = 0; i < n; ++i) {
    BodyId a = 0, b = 0;
    uint32_t feature = 0;
    AnchorState s;
    uint8_t penetrating = 0;
    if (!in->Get(&a) || !in->Get(&b) || !in->Get(&feature) || !in->GetVec3(&s.stretch) || !in->Get(&penetrating) ||
        !in->Get(&s.impact_speed) || !in->Get(&s.rest_depth)) {
      return false;
    }
    s.penetrating = penetrating != 0;
    loaded[{a, b, feature}] = s;
  }
  current_.swap(loaded);
  next_.clear();
  return true;
}

Vec3 ProjectStretch(const Vec3& stretch, const Vec3& n) {
  const Vec3 t = stretch - n * n.dot(stretch);
  const double len = t.norm();
  if (len < 1e-300) return Vec3::Zero();
  return t * (stretch.norm() / len);
}

Vec3 CoulombLimit(const Vec3& trial, double limit, bool* sliding) {
  const double norm = trial.norm();
  *sliding = norm > limit;
  if (!*sliding) return trial;
  return norm > 0.0 ? Vec3(trial * (std::max(limit, 0.0) / norm)) : Vec3::Zero();
}

}  // namespace contactsim
