// The reference broadphase: every pair of boxes is tested, O(n^2). Slow for
// large scenes but obviously right; tests check sweep and prune against it.
#pragma once

#include <vector>

#include "service/collision/broadphase.h"

namespace contactsim {

class NaiveBroadphase : public Broadphase {
 public:
  const char* Name() const override { return "naive"; }
  void FindPairs(const std::vector<Aabb>& boxes, const std::vector<bool>& movable,
                 std::vector<BodyPair>* pairs) override;
};

}  // namespace contactsim
