#include "service/collision/depth_bound.h"

#include <algorithm>
#include <limits>

#include "service/collision/collide_pairs.h"
#include "service/collision/polyhedron_sat.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// m: the narrowphase poses vertices (R v + x) where the support below
// rotates the direction instead; the two differ by round-off, ~1e-15 m
// for bodies of metres, and the bound is kept above either
constexpr double kRoundOff = 1e-9;

// max over one box or hull of u.p (world); +infinity for another shape
// (the pair functions then give no bound)
double PieceSupport(const Shape& shape, const Vec3& x, const Quat& q, const Vec3& u) {
  switch (shape.type) {
    case ShapeType::kBox: return u.dot(x) + shape.half_extents.dot((q.conjugate() * u).cwiseAbs());
    case ShapeType::kConvex: {
      if (shape.hull == nullptr) return kInfinity;
      const ConvexHull& hull = *shape.hull;
      const Vec3 u_body = q.conjugate() * u;
      double min_value;
      if (static_cast<int>(hull.vertices.size()) >= kDescentMinVertices &&
          hull.neighbour_start.size() == hull.vertices.size() + 1) {
        // the least of -u.v is the greatest u.v (convex_hull.h: no local minimum on the graph)
        DescendVertexGraph(hull, 0, [&](int v) { return -u_body.dot(hull.vertices[v]); }, &min_value);
      } else {
        min_value = kInfinity;
        for (const Vec3& v : hull.vertices) min_value = std::min(min_value, -u_body.dot(v));
      }
      return u.dot(x) - min_value;
    }
    default: return kInfinity;
  }
}

// max over the body of u.p, over its children for a compound; a plane's
// only along its outward normal (Direction snaps u to it)
double Support(const RigidBody& body, const Vec3& u) {
  if (body.shape.type == ShapeType::kPlane) {
    Vec3 n;
    double offset;
    PlaneInWorld(body, &n, &offset);
    return u == n ? offset : kInfinity;
  }
  if (body.shape.type != ShapeType::kCompound) return PieceSupport(body.shape, body.x, body.q, u);
  if (body.shape.compound == nullptr) return kInfinity;
  double best = -kInfinity;
  for (const ShapeChild& c : body.shape.compound->children) {
    // the child's world pose, as ChildBody (compound_children.h)
    best = std::max(best, PieceSupport(c.shape, body.x + body.q * c.position, body.q * c.orientation, u));
  }
  return best;
}

// u_AB, or a plane's own normal (from a to b) where u_AB is within 1e-12
// of it: the plane pair's contacts are measured along that normal, and the
// bound is taken there exactly
Vec3 Direction(const RigidBody& a, const RigidBody& b, const Vec3& u_AB) {
  for (const RigidBody* body : {&a, &b}) {
    if (body->shape.type != ShapeType::kPlane) continue;
    Vec3 n;
    double offset;
    PlaneInWorld(*body, &n, &offset);
    const Vec3 n_AB = body == &a ? n : Vec3(-n);
    if (u_AB.dot(n_AB) >= 1.0 - 1e-12) return n_AB;
  }
  return u_AB;
}

}  // namespace

double ContactDepthBound(const RigidBody& a, const RigidBody& b, const Vec3& u_AB) {
  const Vec3 u = Direction(a, b, u_AB);
  const double overlap = Support(a, u) + Support(b, -u);
  if (!(overlap < kInfinity)) return kInfinity;  // also NaN
  return std::max(overlap, 0.0) + kSatMaxBias + kSatAbsTolerance + kRoundOff;
}

}  // namespace contactsim
