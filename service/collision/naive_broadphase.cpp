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
    const Aabb& a = boxes[i];
    for (int j = i + 1; j < n; ++j) {
      const Aabb& b = boxes[j];
      // Aabb::Overlaps with bitwise &: the single comparisons are coin flips
      // a branch predictor loses, their conjunction is almost always false
      // (the benchmark compares this against an equally tuned sweep)
      const bool overlap = (a.min.x() <= b.max.x()) & (b.min.x() <= a.max.x()) & (a.min.y() <= b.max.y()) &
                           (b.min.y() <= a.max.y()) & (a.min.z() <= b.max.z()) & (b.min.z() <= a.max.z());
      if (overlap && (movable_i || movable[j])) pairs->emplace_back(i, j);
    }
  }
}

}  // namespace contactsim
