// Manifold reduction to four points (see manifold_reduction.h).
#include "service/collision/manifold_reduction.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace contactsim {
namespace {

// Index in [0, n) maximising score(i) over the points not yet chosen; -1 if
// every point is chosen. Ties keep the lowest index (deterministic).
template <typename Score>
int ArgMax(size_t n, const std::vector<bool>& chosen, Score score) {
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

}  // namespace

void ReduceManifold(size_t first, ContactSet* contacts) {
  const size_t n = contacts->size() - first;
  if (n <= kMaxManifoldPoints) return;
  const Contact* c = contacts->data() + first;
  const Vec3 normal = c[0].normal;
  std::vector<bool> chosen(n, false);

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

  ContactSet kept;
  for (size_t i = 0; i < n; ++i) {
    if (chosen[i]) kept.push_back(c[i]);
  }
  contacts->resize(first);
  contacts->insert(contacts->end(), kept.begin(), kept.end());
}

}  // namespace contactsim
