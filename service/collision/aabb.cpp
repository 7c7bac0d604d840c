#include "service/collision/aabb.h"

#include <algorithm>
#include <cmath>

#include "service/collision/compound_children.h"
#include "service/collision/triangle_surface.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

// Large but finite, so that sums and sorts stay well defined.
constexpr double kHuge = 1e15;

Aabb PlaneAabb(const RigidBody& body) {
  Aabb box;
  box.min = Vec3::Constant(-kHuge);
  box.max = Vec3::Constant(kHuge);
  const Vec3 n = body.q * body.shape.plane_normal;
  const double offset = body.shape.plane_offset + n.dot(body.x);
  // An axis-aligned half-space n.p <= offset bounds one side of one axis.
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(std::abs(n[axis]) - 1.0) > 1e-12) continue;
    if (n[axis] > 0) box.max[axis] = offset;
    else box.min[axis] = -offset;
  }
  return box;
}

// The union of the children's boxes, then the margin and the sweep of the
// body's own velocity. The body's support vertices serve its child when it
// has one (a link of a model with one collision mesh).
Aabb CompoundAabb(const RigidBody& body, double margin, double dt, AabbSupport* support) {
  Aabb box{Vec3::Constant(kHuge), Vec3::Constant(-kHuge)};
  const auto& children = body.shape.compound->children;
  for (const ShapeChild& child : children) {
    const Aabb c = ComputeAabb(ChildBody(body, child), 0.0, 0.0, children.size() == 1 ? support : nullptr);
    box.min = box.min.cwiseMin(c.min);
    box.max = box.max.cwiseMax(c.max);
  }
  box.Inflate(margin);
  const Vec3 d = body.LinearVelocity() * dt;
  box.min += d.cwiseMin(Vec3::Zero());
  box.max += d.cwiseMax(Vec3::Zero());
  return box;
}

// The box of a mesh's or heightfield's body-frame bounds at the body's pose:
// its eight corners, posed (static, so no sweep).
Aabb SurfaceAabb(const RigidBody& body, double margin) {
  const Aabb local = SurfaceBounds(body.shape);
  const Mat3 R = body.Rotation();
  Aabb box{Vec3::Constant(kHuge), Vec3::Constant(-kHuge)};
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? local.max.x() : local.min.x(), (i & 2) ? local.max.y() : local.min.y(),
                      (i & 4) ? local.max.z() : local.min.z());
    const Vec3 p = body.x + R * corner;
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  box.Inflate(margin);
  return box;
}

// The box of the hull's vertices x + R v, over every vertex.
Aabb HullBoxByScan(const ConvexHull& hull, const Vec3& x, const Mat3& R) {
  Aabb box{Vec3::Constant(kHuge), Vec3::Constant(-kHuge)};
  for (const Vec3& v : hull.vertices) {
    const Vec3 p = x + R * v;
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

bool HasVertexGraph(const ConvexHull& hull) {
  return static_cast<int>(hull.vertices.size()) >= kDescentMinVertices &&
         hull.neighbour_start.size() == hull.vertices.size() + 1;
}

// The same box by six descents; each vertex's x + R v is evaluated as the
// scan evaluates it, so the extremes are the scan's values.
Aabb HullBoxByDescent(const ConvexHull& hull, const Vec3& x, const Mat3& R, AabbSupport* support) {
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
    double low, high;
    (*support)[2 * axis] =
        DescendVertexGraph(hull, (*support)[2 * axis], [&](int i) { return Vec3(x + R * hull.vertices[i])[axis]; }, &low);
    (*support)[2 * axis + 1] = DescendVertexGraph(
        hull, (*support)[2 * axis + 1], [&](int i) { return -Vec3(x + R * hull.vertices[i])[axis]; }, &high);
    box.min[axis] = low;
    box.max[axis] = -high;
  }
  return box;
}

}  // namespace

Aabb ComputeAabb(const RigidBody& body, double margin, double dt) { return ComputeAabb(body, margin, dt, nullptr); }

Aabb ComputeAabb(const RigidBody& body, double margin, double dt, AabbSupport* support) {
  const Shape& s = body.shape;
  if (s.type == ShapeType::kPlane) return PlaneAabb(body);
  if (s.type == ShapeType::kCompound) return CompoundAabb(body, margin, dt, support);
  if (s.IsTriangleSurface()) return SurfaceAabb(body, margin);
  const Mat3 R = body.Rotation();
  Vec3 half;
  switch (s.type) {
    case ShapeType::kSphere: half = Vec3::Constant(s.radius); break;
    case ShapeType::kBox: half = R.cwiseAbs() * s.half_extents; break;
    case ShapeType::kCapsule: half = (R.col(2) * s.half_length).cwiseAbs() + Vec3::Constant(s.radius); break;
    case ShapeType::kConvex: {
      Aabb box = support != nullptr && HasVertexGraph(*s.hull) ? HullBoxByDescent(*s.hull, body.x, R, support)
                                                                : HullBoxByScan(*s.hull, body.x, R);
      box.Inflate(margin);
      const Vec3 d = body.LinearVelocity() * dt;
      box.min += d.cwiseMin(Vec3::Zero());
      box.max += d.cwiseMax(Vec3::Zero());
      return box;
    }
    default: half.setZero(); break;
  }
  Aabb box{body.x - half, body.x + half};
  box.Inflate(margin);
  // Sweep by the step's displacement so a fast body meets what lies ahead.
  const Vec3 d = body.LinearVelocity() * dt;
  box.min += d.cwiseMin(Vec3::Zero());
  box.max += d.cwiseMax(Vec3::Zero());
  return box;
}

}  // namespace contactsim
