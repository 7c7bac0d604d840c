#include "service/physics/collision_filter.h"

namespace contactsim {

void JointPairSet::Add(BodyId a, BodyId b) { ++count_[Key(a, b)]; }

void JointPairSet::Remove(BodyId a, BodyId b) {
  const auto it = count_.find(Key(a, b));
  if (it == count_.end()) return;
  if (--it->second == 0) count_.erase(it);
}

}  // namespace contactsim
