#include "service/collision/naive_broadphase.h"

#include "service/collision/broadphase_check.h"

namespace contactsim {

void NaiveBroadphase::FindPairs(const std::vector<Aabb>& boxes, const std::vector<bool>& movable,
                                std::vector<BodyPair>* pairs) {
  CheckBroadphaseInput(boxes, movable);
  pairs->clear();
  const int n = static_cast<int>(boxes.size());
  // i ascending, then j ascending: the output is sorted without a sort
  for (int i = 0; i < n; ++i) {
    const bool movable_i = movable[i];
    for (int j = i + 1; j < n; ++j) {
      if (!movable_i && !movable[j]) continue;
      if (boxes[i].Overlaps(boxes[j])) pairs->emplace_back(i, j);
    }
  }
}

}  // namespace contactsim
