#include "service/collision/box_tree.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

constexpr int kLeafSize = 4;

// The boxes are computed with rounding (R |h| for a rotated box) and the
// walk's slab test with more; growing each box by far more than either (a
// relative 1e-9) keeps every point of the exact shape inside it, so the walk
// never skips a body the brute force would hit.
Aabb Padded(const Aabb& b) {
  Aabb p = b;
  const double scale = std::max(b.min.cwiseAbs().maxCoeff(), b.max.cwiseAbs().maxCoeff());
  p.Inflate(1e-9 * (1.0 + scale));
  return p;
}

}  // namespace

void BoxTree::Build(const std::vector<Aabb>& boxes) {
  nodes_.clear();
  items_.resize(boxes.size());
  if (boxes.empty()) return;
  std::vector<Aabb> padded(boxes.size());
  std::vector<Vec3> centres(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    items_[i] = static_cast<int>(i);
    padded[i] = Padded(boxes[i]);
    centres[i] = 0.5 * (boxes[i].min + boxes[i].max);
  }
  nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
  nodes_.emplace_back();
  BuildNode(0, padded, centres, 0, static_cast<int>(boxes.size()));
}

void BoxTree::BuildNode(int self, const std::vector<Aabb>& boxes, const std::vector<Vec3>& centres, int begin,
                       int end) {
  Aabb box = boxes[items_[begin]];
  Vec3 c_min = centres[items_[begin]], c_max = c_min;
  for (int i = begin + 1; i < end; ++i) {
    box.min = box.min.cwiseMin(boxes[items_[i]].min);
    box.max = box.max.cwiseMax(boxes[items_[i]].max);
    c_min = c_min.cwiseMin(centres[items_[i]]);
    c_max = c_max.cwiseMax(centres[items_[i]]);
  }
  nodes_[self].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[self].first = begin;
    nodes_[self].count = end - begin;
    return;
  }
  int axis = 0;
  (c_max - c_min).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  // ties by item index, so the tree is a function of the boxes alone
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end, [&](int a, int b) {
    const double ca = centres[a][axis], cb = centres[b][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const int left = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[self].first = left;
  nodes_[self].count = 0;
  BuildNode(left, boxes, centres, begin, mid);
  BuildNode(left + 1, boxes, centres, mid, end);
}

double BoxTree::Enter(const Aabb& box, const Vec3& origin, const Vec3& inv, const Vec3& direction, double best) {
  double t_in = 0.0, t_out = best;
  for (int axis = 0; axis < 3; ++axis) {
    if (direction[axis] == 0.0) {
      if (origin[axis] < box.min[axis] || origin[axis] > box.max[axis]) return kNoEntry;
      continue;
    }
    double t0 = (box.min[axis] - origin[axis]) * inv[axis];
    double t1 = (box.max[axis] - origin[axis]) * inv[axis];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
    if (t_in > t_out) return kNoEntry;
  }
  return t_in;
}

}  // namespace contactsim
