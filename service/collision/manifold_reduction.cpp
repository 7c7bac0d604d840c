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

// Lateral offset of b from a: its part in the contact plane.
Vec3 InPlane(const Vec3& a, const Vec3& b, const Vec3& normal) {
  const Vec3 d = b - a;
  return d - normal.dot(d) * normal;
}

// Whether a and b are level: their depths differ by at most kFlushSlope
// times their in-plane distance.
bool Level(const Contact& a, const Contact& b, const Vec3& normal) {
  return std::abs(a.depth - b.depth) <= kFlushSlope * InPlane(a.point, b.point, normal).norm();
}

// The points of a face that lies flush with the contact plane at the
// deepest point: when the points that no deeper point hides include three
// or more that span such a face, hides every other one and returns how many
// are left (else returns `left`). The face's points are grown from the
// deepest one, deeper first, each joining when it is level with every
// point joined before it. The slope is a ratio, so the rule holds at every
// size, and it tells a face's corners (equal depths, or a face tilted less
// than the slope) from the vertices of its neighbour faces within the
// detection margin, which rise from its rim at their dihedral angle. Those
// reach farther than the face, so Gregorius's widest area kept them over
// the face's own corners: a hull landing flat from 10 cm kept two of its
// face's three corners and two vertices 13-15 mm above it, and penalty's
// impact stage struck the two as an edge and tipped it
// (docs/methods/penalty.md, "Resting hulls"). Level with every member, not
// only with the deepest: a long narrow flat's neighbour rises gently seen
// from the flat's far end, steeply from its near one (a 71-sided wheel's
// flats, 0.09 rad apart, are 9 mm wide and 5 cm long). The points must span
// a face, not a sliver: their widest triangle (the deepest, the farthest
// from it, the widest with the two) at least kMinFaceWidth of its long side
// wide, and its own depth slope below kFlushSlope (on a face tilted more,
// points level pairwise lie along its level lines). `visited` and `outside`
// are scratch flags for n points.
size_t HideAllButFlushFace(const Contact* c, size_t n, const Vec3& normal, bool* hidden, bool* visited,
                           bool* outside, size_t left) {
  std::copy(hidden, hidden + n, visited);
  std::fill(outside, outside + n, true);
  size_t level = 0;
  int i0 = -1;
  for (int j; (j = ArgMax(n, visited, [&](size_t i) { return c[i].depth; })) >= 0;) {
    visited[j] = true;
    bool joins = true;
    for (size_t k = 0; k < n && joins; ++k) joins = outside[k] || Level(c[j], c[k], normal);
    if (!joins) continue;
    outside[j] = false;
    ++level;
    if (i0 < 0) i0 = j;
  }
  if (level < 3) return left;
  outside[i0] = true;
  const int i1 = ArgMax(n, outside, [&](size_t i) { return InPlane(c[i0].point, c[i].point, normal).squaredNorm(); });
  outside[i1] = true;
  const Vec3 u = InPlane(c[i0].point, c[i1].point, normal);
  const int i2 = ArgMax(n, outside, [&](size_t i) {
    return std::abs(u.cross(InPlane(c[i0].point, c[i].point, normal)).dot(normal));
  });
  const Vec3 v = InPlane(c[i0].point, c[i2].point, normal);
  // twice the triangle's signed area, and its depth gradient times that
  const double area2 = u.cross(v).dot(normal);
  const Vec3 slope_area2 =
      (c[i1].depth - c[i0].depth) * v.cross(normal) - (c[i2].depth - c[i0].depth) * u.cross(normal);
  // width |area2| / |u| against kMinFaceWidth |u|
  const bool wide = std::abs(area2) >= kMinFaceWidth * u.squaredNorm();
  if (!wide || !(slope_area2.norm() <= kFlushSlope * std::abs(area2))) return left;
  outside[i0] = outside[i1] = false;
  for (size_t i = 0; i < n; ++i) hidden[i] = hidden[i] || outside[i];
  return level;
}

// Marks in `chosen` (where the points already chosen or hidden are
// marked) Gregorius's four: the deepest, the farthest from it, the largest
// triangle with the two, the most area added to it. Returns whether they
// are pairwise level (so lie flush, or on a face tilted less than
// kFlushSlope). Needs more than four unmarked points.
bool ChooseFour(const Contact* c, size_t n, const Vec3& normal, bool* chosen) {
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
  const int four[4] = {i0, i1, i2, i3};
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      if (!Level(c[four[a]], c[four[b]], normal)) return false;
    }
  }
  return true;
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
  bool inline_flags[4 * kInlinePoints];
  std::unique_ptr<bool[]> heap_flags;
  bool* flags = inline_flags;
  if (n > kInlinePoints) {
    heap_flags.reset(new bool[4 * n]);
    flags = heap_flags.get();
  }
  bool* chosen = flags;
  bool* hidden = flags + n;
  bool* scratch = flags + 2 * n;  // two arrays
  std::fill(flags, flags + 2 * n, false);
  const Contact* c = contacts->data() + first;
  const Vec3 normal = c[0].normal;
  // a hidden point is never chosen: it counts as chosen for ArgMax, and
  // is left out below; when four or fewer are left they are the manifold
  size_t left = HideShadowedPoints(c, n, normal, hidden);
  std::copy(hidden, hidden + n, chosen);
  // four that are not all level may have passed over a face flush at the
  // deepest point: then the face's points are chosen among (the four
  // would be the same had they all been the face's)
  if (left > kMaxManifoldPoints && !ChooseFour(c, n, normal, chosen)) {
    const size_t face = HideAllButFlushFace(c, n, normal, hidden, scratch, scratch + n, left);
    if (face < left) {
      left = face;
      std::copy(hidden, hidden + n, chosen);
      if (left > kMaxManifoldPoints) ChooseFour(c, n, normal, chosen);
    }
  }
  // four or fewer left are the manifold
  for (size_t i = 0; i < n; ++i) chosen[i] = left <= kMaxManifoldPoints ? !hidden[i] : chosen[i] && !hidden[i];
  KeepMarked(first, n, chosen, contacts);
}

}  // namespace contactsim
