#include "service/collision/triangle_surface.h"

#include <algorithm>

namespace contactsim {
namespace {

// A triangle whose doubled area is below this fraction of its longest edge
// squared has zero area to round-off (a sliver thinner than 1e-12 of its length).
constexpr double kDegenerateRatio = 1e-12;

}  // namespace

bool EdgeIsActive(const Vec3& n, const Vec3& a, const Vec3& b, const Vec3& w, double angle) {
  // the neighbour wound as this triangle: edge b -> a, then w
  const Vec3 m = (a - b).cross(w - b);
  const double len = m.norm();
  if (!(len > 0.0)) return true;  // a degenerate neighbour: keep the edge
  const bool convex = n.dot(w - a) < 0.0;
  return convex && n.dot(m / len) < std::cos(angle);
}

bool MakeSurfaceTriangle(const Vec3& a, const Vec3& b, const Vec3& c, SurfaceTriangle* tri) {
  const Vec3 n = (b - a).cross(c - a);
  const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  const double area2 = n.norm();
  if (!(area2 > kDegenerateRatio * longest) || !(longest > 0.0)) return false;
  tri->v = {a, b, c};
  tri->normal = n / area2;
  return true;
}

Aabb SurfaceBounds(const Shape& shape) {
  if (shape.type == ShapeType::kMesh && shape.mesh != nullptr) return shape.mesh->bounds;
  if (shape.type == ShapeType::kHeightfield && shape.heightfield != nullptr) return shape.heightfield->Bounds();
  return Aabb{};
}

SurfaceTriangle TriangleInWorld(const SurfaceTriangle& tri, const Mat3& R, const Vec3& x) {
  SurfaceTriangle w = tri;
  for (int k = 0; k < 3; ++k) w.v[k] = R * tri.v[k] + x;
  w.normal = R * tri.normal;
  return w;
}

Aabb BoxInBodyFrame(const Aabb& world, const Mat3& R, const Vec3& x) {
  const Mat3 Rt = R.transpose();
  Aabb local{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? world.max.x() : world.min.x(), (i & 2) ? world.max.y() : world.min.y(),
                      (i & 4) ? world.max.z() : world.min.z());
    const Vec3 p = Rt * (corner - x);
    local.min = local.min.cwiseMin(p);
    local.max = local.max.cwiseMax(p);
  }
  return local;
}

}  // namespace contactsim
