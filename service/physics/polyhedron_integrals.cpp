// Exact volume, first and second moments of a polyhedron.
//
// For a tetrahedron with vertices v0..v3 and signed volume
// V = det[v1 - v0, v2 - v0, v3 - v0] / 6, the moments are (Tonon 2004,
// "Explicit exact formulas for the 3-D tetrahedron inertia tensor"):
//   integral of p       = V (v0 + v1 + v2 + v3) / 4
//   integral of p p^T   = V / 20 (sum_k v_k v_k^T + s s^T),  s = sum_k v_k.
// A closed, outward-oriented surface fanned about a reference point r gives
// signed tetrahedra whose sum is the solid (divergence theorem; Mirtich 1996
// computes the same integrals through face projections).
#include "service/physics/polyhedron_integrals.h"

#include <cstddef>

namespace contactsim {

PolyhedronIntegrals ComputePolyhedronIntegrals(const ConvexHull& hull) {
  PolyhedronIntegrals out;
  if (hull.vertices.empty()) return out;

  // the vertex mean as the fan apex keeps the terms small, so large offsets
  // of the input frame do not cancel catastrophically
  Vec3 r = Vec3::Zero();
  for (const Vec3& v : hull.vertices) r += v;
  r /= static_cast<double>(hull.vertices.size());

  double volume = 0.0;
  Vec3 first = Vec3::Zero();    // integral of (p - r)
  Mat3 second = Mat3::Zero();   // integral of (p - r)(p - r)^T
  for (const ConvexHull::Face& face : hull.faces) {
    const std::vector<int>& loop = face.vertices;
    if (loop.size() < 3) continue;
    const Vec3 a = hull.vertices[loop[0]] - r;
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const Vec3 b = hull.vertices[loop[k]] - r;
      const Vec3 c = hull.vertices[loop[k + 1]] - r;
      // apex at the origin (= r): v0 = 0 drops out of both sums
      const double v = a.dot(b.cross(c)) / 6.0;
      const Vec3 s = a + b + c;
      volume += v;
      first += v * s / 4.0;
      second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  }
  out.volume = volume;
  if (volume <= 0.0) return out;
  const Vec3 d = first / volume;  // centroid - r
  out.centroid = r + d;
  // parallel axis theorem for the second moment: C_r = C_g + V d d^T
  out.second_moment = second - volume * d * d.transpose();
  return out;
}

}  // namespace contactsim
