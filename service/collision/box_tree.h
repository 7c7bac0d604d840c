// A bounding-volume tree over boxes, built top down by splitting each node's
// boxes at the median centre along its longest axis (Wald 2007, "On fast
// construction of SAH-based bounding volume hierarchies", the median split
// as the cheap baseline), stored flat with each node's children adjacent.
// Two queries: a ray walk (built once per ray batch, ray_cast.h), which
// visits the nearer child first and skips a node whose box the ray enters
// beyond the best hit so far; and a box query (built once per triangle mesh,
// triangle_mesh.h), which visits the items whose boxes overlap a body's box,
// so that colliding a body with a mesh costs the triangles near the body.
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/aabb.h"

namespace contactsim {

class BoxTree {
 public:
  // `boxes[i]` bounds item i; items are reported by that index.
  void Build(const std::vector<Aabb>& boxes);

  // Calls visit(item, best) for every item whose box the ray (origin,
  // unit direction) meets within [0, *best]; visit may lower *best.
  // A box entered at exactly `best` is still visited, so that a tie in
  // distance is settled by the caller, not by the walk's order.
  template <class Visit>
  void Walk(const Vec3& origin, const Vec3& direction, double* best, Visit&& visit) const;

  // Calls visit(item) for every item whose box overlaps `box`, in tree order.
  template <class Visit>
  void Overlap(const Aabb& box, Visit&& visit) const;

  bool empty() const { return nodes_.empty(); }
  static constexpr double kNoEntry = 1e300;

 private:
  struct Node {
    Aabb box;
    int first = 0;  // leaf: first of items_; inner: index of the left child (right = first + 1)
    int count = 0;  // leaf: number of items; 0 for an inner node
  };
  void BuildNode(int self, const std::vector<Aabb>& boxes, const std::vector<Vec3>& centres, int begin, int end);
  // The entry distance of the ray into a node's box, or +inf when it
  // misses the box or enters it beyond `best`.
  static double Enter(const Aabb& box, const Vec3& origin, const Vec3& inv, const Vec3& direction, double best);
  std::vector<Node> nodes_;
  std::vector<int> items_;
};

template <class Visit>
void BoxTree::Walk(const Vec3& origin, const Vec3& direction, double* best, Visit&& visit) const {
  if (nodes_.empty()) return;
  const Vec3 inv = direction.cwiseInverse();
  struct Pending {
    int node;
    double t;
  };
  Pending stack[96];  // depth <= log2(items) + 1 for median splits; 2 per level
  int top = 0;
  double t_root = Enter(nodes_[0].box, origin, inv, direction, *best);
  if (t_root == kNoEntry) return;
  stack[top++] = {0, t_root};
  while (top > 0) {
    const Pending p = stack[--top];
    if (p.t > *best) continue;
    const Node& n = nodes_[p.node];
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) visit(items_[i], best);
      continue;
    }
    const double t_l = Enter(nodes_[n.first].box, origin, inv, direction, *best);
    const double t_r = Enter(nodes_[n.first + 1].box, origin, inv, direction, *best);
    // push the farther first, so the nearer is walked first
    if (t_l <= t_r) {
      if (t_r != kNoEntry) stack[top++] = {n.first + 1, t_r};
      if (t_l != kNoEntry) stack[top++] = {n.first, t_l};
    } else {
      if (t_l != kNoEntry) stack[top++] = {n.first, t_l};
      if (t_r != kNoEntry) stack[top++] = {n.first + 1, t_r};
    }
  }
}

template <class Visit>
void BoxTree::Overlap(const Aabb& box, Visit&& visit) const {
  if (nodes_.empty() || !nodes_[0].box.Overlaps(box)) return;
  int stack[96];  // depth <= log2(items) + 1 for median splits; 2 per level
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (n.count > 0) {
      for (int i = n.first; i < n.first + n.count; ++i) visit(items_[i]);
      continue;
    }
    // right first, so the left subtree is visited first
    if (nodes_[n.first + 1].box.Overlaps(box)) stack[top++] = n.first + 1;
    if (nodes_[n.first].box.Overlaps(box)) stack[top++] = n.first;
  }
}

}  // namespace contactsim
