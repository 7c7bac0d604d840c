// Per-pair separating-axis memory (see separating_axis_cache.h).
#include "service/collision/separating_axis_cache.h"

namespace contactsim {

const SeparatingAxis* SeparatingAxisCache::Find(BodyId a, BodyId b) const {
  const auto it = axes_.find({a, b});
  return it == axes_.end() ? nullptr : &it->second;
}

void SeparatingAxisCache::Store(BodyId a, BodyId b, const SeparatingAxis& axis) { axes_[{a, b}] = axis; }

void SeparatingAxisCache::Erase(BodyId a, BodyId b) { axes_.erase({a, b}); }

void SeparatingAxisCache::Clear() {
  axes_.clear();
  hits_ = 0;
  misses_ = 0;
}

}  // namespace contactsim
