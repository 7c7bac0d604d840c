// Signed distance to boxes and convex polyhedra (see polyhedron_distance.h).
#include "service/collision/polyhedron_distance.h"

#include <cmath>
#include <limits>

#include "service/collision/closest_points.h"

namespace contactsim {
namespace {

// Below this distance (m) the direction p - q is round-off, so the nearest
// face normal is used instead; 1e-12 m is far below any contact tolerance.
constexpr double kTinyDistance = 1e-12;

}  // namespace

SurfaceQuery BoxSignedDistance(const RigidBody& box, const Vec3& p_W) {
  const Mat3 R = box.Rotation();
  const Vec3& h = box.shape.half_extents;
  const Vec3 p = R.transpose() * (p_W - box.x);
  const Vec3 q = p.cwiseMax(-h).cwiseMin(h);
  SurfaceQuery out;
  const double d = (p - q).norm();
  if (d > kTinyDistance) {
    // outside: nearest point is the clamped point
    out.distance = d;
    out.point = R * q + box.x;
    out.normal = R * ((p - q) / d);
    out.feature = (p.x() > h.x()) + 3 * (p.x() < -h.x()) + 9 * ((p.y() > h.y()) + 3 * (p.y() < -h.y())) +
                  27 * ((p.z() > h.z()) + 3 * (p.z() < -h.z()));
    return out;
  }
  // inside (or on the surface): nearest face is the one with least clearance
  int axis = 0;
  double clearance = h.x() - std::abs(p.x());
  for (int k = 1; k < 3; ++k) {
    const double c = h[k] - std::abs(p[k]);
    if (c < clearance) {
      clearance = c;
      axis = k;
    }
  }
  const double sign = p[axis] >= 0.0 ? 1.0 : -1.0;
  Vec3 n = Vec3::Zero();
  n[axis] = sign;
  Vec3 on_face = p;
  on_face[axis] = sign * h[axis];
  out.distance = -clearance;
  out.point = R * on_face + box.x;
  out.normal = R * n;
  out.feature = 100 + 2 * axis + (sign > 0.0 ? 0 : 1);
  return out;
}

SurfaceQuery PolyhedronSignedDistance(const PosedPolyhedron& poly, const Vec3& p_W) {
  // largest face-plane distance: the signed distance when inside
  int best_face = 0;
  double max_plane = -std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < poly.normals.size(); ++f) {
    const double s = poly.normals[f].dot(p_W) - poly.offsets[f];
    if (s > max_plane) {
      max_plane = s;
      best_face = static_cast<int>(f);
    }
  }
  SurfaceQuery out;
  if (max_plane <= kTinyDistance) {
    out.distance = max_plane;
    out.normal = poly.normals[best_face];
    out.point = p_W - max_plane * out.normal;
    out.feature = best_face;
    return out;
  }
  // outside: nearest point over the faces that p lies in front of
  double best_sq = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < poly.normals.size(); ++f) {
    const Vec3& n = poly.normals[f];
    const double s = n.dot(p_W) - poly.offsets[f];
    if (s <= 0.0) continue;
    const Vec3 projected = p_W - s * n;
    const std::vector<int>& loop = poly.topology->faces[f].vertices;
    bool inside = true;
    Vec3 nearest = projected;
    double nearest_sq = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < loop.size(); ++k) {
      const Vec3& v0 = poly.vertices[loop[k]];
      const Vec3& v1 = poly.vertices[loop[(k + 1) % loop.size()]];
      // edge x normal points out of a counter-clockwise face
      if ((v1 - v0).cross(n).dot(projected - v0) > 0.0) inside = false;
      const Vec3 c = ClosestPointOnSegment(p_W, v0, v1);
      const double d_sq = (p_W - c).squaredNorm();
      if (d_sq < nearest_sq) {
        nearest_sq = d_sq;
        nearest = c;
      }
    }
    if (inside) {
      nearest = projected;
      nearest_sq = s * s;
    }
    if (nearest_sq < best_sq) {
      best_sq = nearest_sq;
      out.point = nearest;
      out.normal = inside ? n : Vec3::Zero();  // an edge's or vertex's normal follows below
      out.feature = static_cast<int>(f);
    }
  }
  out.distance = std::sqrt(best_sq);
  // nearest point on an edge or vertex: the normal points from it to p,
  // normalised from the difference itself (dividing by the distance found
  // from the squared norm leaves it off unit by the difference's round-off,
  // eps |p| / d, for p near the surface)
  if (out.normal.isZero()) {
    const Vec3 v = p_W - out.point;
    out.normal = out.distance > kTinyDistance ? Vec3(v / v.norm()) : poly.normals[best_face];
  }
  return out;
}

}  // namespace contactsim
