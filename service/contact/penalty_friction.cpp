#include "service/contact/penalty_friction.h"

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

void FrictionAnchors::Commit() {
  current_.swap(next_);
  next_.clear();
}

void FrictionAnchors::Clear() {
  current_.clear();
  next_.clear();
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
