// Disjoint sets over 0..n-1 (union by smaller index, path halving): contact
// islands of the penalty solve, components and loops of the joint graph.
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

namespace contactsim {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Root(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // the smaller index becomes the root, so sets are named by their first
  // element (deterministic); false when i and j were already joined
  bool Join(int i, int j) {
    i = Root(i);
    j = Root(j);
    if (i == j) return false;
    parent_[std::max(i, j)] = std::min(i, j);
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace contactsim
