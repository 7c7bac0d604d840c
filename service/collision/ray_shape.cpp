#include "service/collision/ray_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "service/collision/triangle_surface.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The interval of a line inside an intersection of half-spaces n . p <= d
// (Cyrus and Beck 1978, "Generalized two- and three-dimensional clipping"):
// each plane the ray enters raises t_in, each it leaves lowers t_out; a ray
// parallel to a plane (n . u == 0) is either inside it for all t or never.
struct Clip {
  double t_in = -kInf, t_out = kInf;
  Vec3 normal_in = Vec3::Zero();
  bool empty = false;

  void Plane(const Vec3& n, double offset, const Vec3& o, const Vec3& u) {
    const double dist = n.dot(o) - offset;  // > 0: outside this plane
    const double denom = n.dot(u);
    if (denom == 0.0) {
      if (dist > 0.0) empty = true;
      return;
    }
    const double t = -dist / denom;
    if (denom < 0.0) {
      if (t > t_in) {
        t_in = t;
        normal_in = n;
      }
    } else {
      t_out = std::min(t_out, t);
    }
  }

  RayShapeResult Finish(double max_distance, RayShapeHit* hit) const {
    if (empty || t_in > t_out || t_out < 0.0) return RayShapeResult::kMiss;
    if (t_in <= 0.0) return RayShapeResult::kInside;
    if (t_in > max_distance) return RayShapeResult::kMiss;
    hit->t = t_in;
    hit->normal = normal_in;
    return RayShapeResult::kHit;
  }
};

// Entry of the ray into the sphere |p - c| <= r from outside, or +inf. The
// chord is measured from the point of closest approach rather than by the
// quadratic's discriminant, which cancels for distant origins (Haines et al.
// 2019, "Precision improvements for ray/sphere intersection", Ray Tracing
// Gems ch. 7).
double SphereEntry(const Vec3& c, double r, const Vec3& o, const Vec3& u) {
  const Vec3 f = o - c;
  const double t_c = -f.dot(u);
  const Vec3 closest = f + t_c * u;
  const double h2 = r * r - closest.squaredNorm();
  if (h2 < 0.0) return kInf;
  const double t = t_c - std::sqrt(h2);
  return t >= 0.0 ? t : kInf;
}

RayShapeResult Sphere(double r, const Vec3& o, const Vec3& u, double max_distance, RayShapeHit* hit) {
  if (o.squaredNorm() <= r * r) return RayShapeResult::kInside;
  const double t = SphereEntry(Vec3::Zero(), r, o, u);
  if (t > max_distance) return RayShapeResult::kMiss;
  hit->t = t;
  hit->normal = (o + t * u).normalized();
  return RayShapeResult::kHit;
}

// Entry through the side of the cylinder x^2 + y^2 <= r^2, |z| <= h, or
// +inf; the caps lie inside the capsule's end spheres, which enter earlier.
double CylinderSideEntry(double r, double h, const Vec3& o, const Vec3& u) {
  const double a = u.x() * u.x() + u.y() * u.y();
  if (a == 0.0) return kInf;
  const double t_c = -(o.x() * u.x() + o.y() * u.y()) / a;
  const double cx = o.x() + t_c * u.x(), cy = o.y() + t_c * u.y();
  const double h2 = r * r - (cx * cx + cy * cy);
  if (h2 < 0.0) return kInf;
  const double t = t_c - std::sqrt(h2 / a);
  if (t < 0.0 || std::abs(o.z() + t * u.z()) > h) return kInf;
  return t;
}

// The capsule is the union of the side cylinder and the two end spheres;
// from a point outside all three, the ray enters the union where it enters
// the first of them.
RayShapeResult Capsule(double r, double h, const Vec3& o, const Vec3& u, double max_distance, RayShapeHit* hit) {
  const Vec3 axis_point(0.0, 0.0, std::clamp(o.z(), -h, h));
  if ((o - axis_point).squaredNorm() <= r * r) return RayShapeResult::kInside;
  const double t = std::min({CylinderSideEntry(r, h, o, u), SphereEntry(Vec3(0, 0, h), r, o, u),
                             SphereEntry(Vec3(0, 0, -h), r, o, u)});
  if (t > max_distance) return RayShapeResult::kMiss;
  const Vec3 p = o + t * u;
  hit->t = t;
  hit->normal = (p - Vec3(0.0, 0.0, std::clamp(p.z(), -h, h))).normalized();
  return RayShapeResult::kHit;
}

RayShapeResult Box(const Vec3& half, const Vec3& o, const Vec3& u, double max_distance, RayShapeHit* hit) {
  Clip clip;  // the slab test: two planes per axis
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3 n = Vec3::Unit(axis);
    clip.Plane(n, half[axis], o, u);
    clip.Plane(-n, half[axis], o, u);
  }
  return clip.Finish(max_distance, hit);
}

RayShapeResult Hull(const ConvexHull& hull, const Vec3& o, const Vec3& u, double max_distance, RayShapeHit* hit) {
  Clip clip;
  for (const ConvexHull::Face& f : hull.faces) clip.Plane(f.normal, f.offset, o, u);
  return clip.Finish(max_distance, hit);
}

RayShapeResult Compound(const CompoundShape& compound, const Vec3& o, const Vec3& u, double max_distance,
                        RayShapeHit* hit) {
  // each child in its own frame; the nearest entry wins, the first child on
  // a tie, and a start inside any child is inside the body
  RayShapeResult result = RayShapeResult::kMiss;
  for (const ShapeChild& child : compound.children) {
    const Quat to_child = child.orientation.conjugate();
    RayShapeHit h;
    const RayShapeResult r =
        RayCastShape(child.shape, to_child * (o - child.position), to_child * u, max_distance, &h);
    if (r == RayShapeResult::kInside) return r;
    if (r == RayShapeResult::kHit && (result == RayShapeResult::kMiss || h.t < hit->t)) {
      result = r;
      hit->t = h.t;
      hit->normal = child.orientation * h.normal;
    }
  }
  return result;
}

// The front face of one triangle (Moller and Trumbore 1997, "Fast,
// minimum storage ray-triangle intersection"): t along u when the ray
// enters from the front within (0, *best]; a surface has no inside.
bool RayTriangle(const SurfaceTriangle& tri, const Vec3& o, const Vec3& u, double* best) {
  if (u.dot(tri.normal) >= 0.0) return false;  // from behind or along it
  const Vec3 e1 = tri.v[1] - tri.v[0], e2 = tri.v[2] - tri.v[0];
  const Vec3 p = u.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return false;
  const Vec3 s = o - tri.v[0];
  const double bu = s.dot(p) / det;
  if (bu < 0.0 || bu > 1.0) return false;
  const Vec3 q = s.cross(e1);
  const double bv = u.dot(q) / det;
  if (bv < 0.0 || bu + bv > 1.0) return false;
  const double t = e2.dot(q) / det;
  if (!(t > 0.0 && t <= *best)) return false;
  *best = t;
  return true;
}

// A mesh by its box tree, a heightfield by the cells under the ray's box;
// the nearest front face wins.
RayShapeResult Surface(const Shape& shape, const Vec3& o, const Vec3& u, double max_distance, RayShapeHit* hit) {
  double best = max_distance;
  bool found = false;
  auto visit = [&](const SurfaceTriangle& tri) {
    if (RayTriangle(tri, o, u, &best)) {
      found = true;
      hit->normal = tri.normal;
    }
  };
  if (shape.type == ShapeType::kMesh && shape.mesh != nullptr) {
    const TriangleMesh& mesh = *shape.mesh;
    mesh.tree.Walk(o, u, &best, [&](int t, double*) { visit(mesh.Triangle(t)); });
  } else if (shape.type == ShapeType::kHeightfield && shape.heightfield != nullptr) {
    // the segment's box, cut to the field's so a long ray stays bounded
    const Aabb bounds = shape.heightfield->Bounds();
    const Vec3 end = o + std::min(max_distance, 1e12) * u;
    Aabb box{o.cwiseMin(end).cwiseMax(bounds.min), o.cwiseMax(end).cwiseMin(bounds.max)};
    shape.heightfield->ForEachTriangle(box, visit);
  }
  if (!found) return RayShapeResult::kMiss;
  hit->t = best;
  return RayShapeResult::kHit;
}

}  // namespace

RayShapeResult RayCastShape(const Shape& shape, const Vec3& origin, const Vec3& direction, double max_distance,
                            RayShapeHit* hit) {
  switch (shape.type) {
    case ShapeType::kSphere: return Sphere(shape.radius, origin, direction, max_distance, hit);
    case ShapeType::kBox: return Box(shape.half_extents, origin, direction, max_distance, hit);
    case ShapeType::kCapsule: return Capsule(shape.radius, shape.half_length, origin, direction, max_distance, hit);
    case ShapeType::kConvex: return Hull(*shape.hull, origin, direction, max_distance, hit);
    case ShapeType::kPlane: {
      Clip clip;
      clip.Plane(shape.plane_normal, shape.plane_offset, origin, direction);
      return clip.Finish(max_distance, hit);
    }
    case ShapeType::kCompound: return Compound(*shape.compound, origin, direction, max_distance, hit);
    case ShapeType::kMesh:
    case ShapeType::kHeightfield: return Surface(shape, origin, direction, max_distance, hit);
    default: return RayShapeResult::kMiss;
  }
}

}  // namespace contactsim
