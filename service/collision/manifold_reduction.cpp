// Manifold reduction to four points (see manifold_reduction.h).
#include "service/collision/manifold_reduction.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace contactsim {
namespace {

// Index in [0, n) maximising score(i) over the points not yet chosen; -1 if
// every point is chosen. Ties keep the lowest index (deterministic).
template <typename Score>
int ArgMax(size_t n, const bool* chosen, Score score) {
  int best = -1;
  double best_score = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (chosen[i]) continue;
    const double s = score(i);
    if (best < 0 || s > best_score) {
      best = static_cast<int>(i);
      best_score = s;
    }
  }
  return best;
}

// Marks in `hidden` the points that lie behind a deeper one: within the
// cone of half-angle 45 degrees above it, |in-plane offset| <= the depth
// difference. Such a point supports nothing
// the deeper one does not, but its 3D distance and, in a near tie, its
// index could win it a place over the deeper one: a thin plate spun on the
// ground (its top face within the detection reach) kept two top corners
// and stood on two of its four bottom ones. Returns how many are left.
size_t HideShadowedPoints(const Contact* c, size_t n, const Vec3& normal, bool* hidden) {
  size_t left = n;
  for (size_t j = 0; j < n; ++j) {
    for (size_t i = 0; i < n && !hidden[j]; ++i) {
      if (i == j) continue;
      const double deeper = c[i].depth - c[j].depth;
      if (!(deeper > 0.0)) continue;
      const Vec3 d = c[j].point - c[i].point;
      const Vec3 in_plane = d - normal.dot(d) * normal;
      if (in_plane.norm() <= deeper) {
        hidden[j] = true;
        --left;
      }
    }
  }
  return left;
}

// Keeps the points [first, first + n) marked in `keep`, in their order, by
// moving them down over the others (a kept point never moves up).
void KeepMarked(size_t first, size_t n, const bool* keep, ContactSet* contacts) {
  Contact* c = contacts->data() + first;
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    if (keep[i]) c[kept++] = c[i];
  }
  contacts->resize(first + kept);
}

// The flags of up to kInlinePoints points live on the stack: a box pair's
// clipped polygon has at most 8, and a heap allocation a reduced manifold
// cost as much as the reduction itself.
constexpr size_t kInlinePoints = 64;

}  // namespace

void ReduceManifold(size_t first, ContactSet* contacts) {
  const size_t n = contacts->size() - first;
  if (n <= kMaxManifoldPoints) return;
  bool inline_flags[2 * kInlinePoints];
  std::unique_ptr<bool[]> heap_flags;
  bool* flags = inline_flags;
  if (n > kInlinePoints) {
    heap_flags.reset(new bool[2 * n]);
    flags = heap_flags.get();
  }
  bool* chosen = flags;
  bool* hidden = flags + n;
  std::fill(flags, flags + 2 * n, false);
  const Contact* c = contacts->data() + first;
  const Vec3 normal = c[0].normal;
  // a hidden point is never chosen: it counts as chosen for ArgMax, and
  // is left out below; when four or fewer are left they are the manifold
  if (HideShadowedPoints(c, n, normal, hidden) <= kMaxManifoldPoints) {
    for (size_t i = 0; i < n; ++i) chosen[i] = !hidden[i];
    KeepMarked(first, n, chosen, contacts);
    return;
  }
  std::copy(hidden, hidden + n, chosen);

  // deepest point
  const int i0 = ArgMax(n, chosen, [&](size_t i) { return c[i].depth; });
  chosen[i0] = true;
  // farthest from it
  const int i1 = ArgMax(n, chosen, [&](size_t i) { return (c[i].point - c[i0].point).squaredNorm(); });
  chosen[i1] = true;
  // largest triangle with the two, on either side of their line
  const int i2 = ArgMax(n, chosen, [&](size_t i) {
    return std::abs((c[i1].point - c[i0].point).cross(c[i].point - c[i0].point).dot(normal));
  });
  chosen[i2] = true;
  // most area added outside the triangle: the largest negative signed area
  // against any of its edges, with the triangle oriented counter-clockwise
  const Vec3 p[3] = {c[i0].point, c[i1].point, c[i2].point};
  const double orientation = (p[1] - p[0]).cross(p[2] - p[0]).dot(normal) >= 0.0 ? 1.0 : -1.0;
  const int i3 = ArgMax(n, chosen, [&](size_t i) {
    double added = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& e0 = p[k];
      const Vec3& e1 = p[(k + 1) % 3];
      const double signed_area = orientation * (e1 - e0).cross(c[i].point - e0).dot(normal);
      added = std::max(added, -signed_area);
    }
    return added;
  });
  chosen[i3] = true;
  for (size_t i = 0; i < n; ++i) chosen[i] = chosen[i] && !hidden[i];
  KeepMarked(first, n, chosen, contacts);
}

}  // namespace contactsim
