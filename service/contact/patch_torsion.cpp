#include "service/contact/patch_torsion.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

using Vec2 = Eigen::Vector2d;

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The convex hull of `p` counter-clockwise (Andrew's monotone chain),
// without collinear points.
std::vector<Vec2> PlanarHull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Vec2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && Cross(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && Cross(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

// integral of |x| over the triangle (0, v0, v1): in polar coordinates about
// the origin, with h the distance of the edge's line and s the coordinate
// along it from the foot of the perpendicular,
//   integral r^2 dr dphi = (h^3 / 3) integral sec^3 phi dphi
//                        = [h s sqrt(h^2 + s^2) + h^3 asinh(s / h)] / 6.
double TriangleMoment(const Vec2& v0, const Vec2& v1) {
  const Vec2 edge = v1 - v0;
  const double length = edge.norm();
  if (!(length > 0.0)) return 0.0;
  const Vec2 e = edge / length;
  const double h = std::abs(Cross(e, v0));
  if (!(h > 0.0)) return 0.0;
  auto f = [h](double s) { return h * s * std::sqrt(h * h + s * s) + h * h * h * std::asinh(s / h); };
  return (f(v1.dot(e)) - f(v0.dot(e))) / 6.0;
}

}  // namespace

Status RefusePatchTorsion(const char* method, const ParamMap& params, const char* why) {
  if (params.count("patch_torsion") == 0) return Status::Ok();
  return Status::InvalidArgument(std::string("patch_torsion is not a parameter of contact method ") + method + ": " +
                                 why + " (impulse, lcp, soft and xpbd take it)");
}

double UniformPatchRadius(const Vec3* points, int count, const Vec3& n, Vec3* centroid) {
  *centroid = Vec3::Zero();
  if (count < 3) return 0.0;
  Vec3 t1, t2;
  PerpendicularBasis(n, &t1, &t2);
  const Vec3 origin = points[0];
  std::vector<Vec2> plane(count);
  for (int i = 0; i < count; ++i) plane[i] = Vec2(t1.dot(points[i] - origin), t2.dot(points[i] - origin));
  const std::vector<Vec2> hull = PlanarHull(plane);
  // area and centroid by the triangles fanning from the hull's first vertex
  double area = 0.0;
  Vec2 c = Vec2::Zero();
  for (size_t i = 1; i + 1 < hull.size(); ++i) {
    const double a = 0.5 * Cross(hull[i] - hull[0], hull[i + 1] - hull[0]);
    area += a;
    c += a * (hull[0] + hull[i] + hull[i + 1]) / 3.0;
  }
  double extent = 0.0;
  for (const Vec2& v : hull) extent = std::max(extent, (v - hull[0]).norm());
  if (hull.size() < 3 || !(area > 1e-9 * extent * extent)) return 0.0;
  c /= area;
  double moment = 0.0;
  for (size_t i = 0; i < hull.size(); ++i) moment += TriangleMoment(hull[i] - c, hull[(i + 1) % hull.size()] - c);
  const Vec3 in_plane = c.x() * t1 + c.y() * t2;
  // the centroid at the points' mean height along n
  double height = 0.0;
  for (int i = 0; i < count; ++i) height += n.dot(points[i] - origin) / count;
  *centroid = origin + in_plane + height * n;
  return moment / area;
}

void PatchFrictionPoints(const ContactSet& contacts, std::vector<Vec3>* points) {
  points->resize(contacts.size());
  std::vector<Vec3> patch;
  for (size_t first = 0; first < contacts.size();) {
    const Contact& c0 = contacts[first];
    size_t end = first + 1;
    while (end < contacts.size() && contacts[end].a == c0.a && contacts[end].b == c0.b &&
           contacts[end].normal.dot(c0.normal) >= 1.0 - 1e-9) {
      ++end;
    }
    patch.clear();
    for (size_t k = first; k < end; ++k) patch.push_back(contacts[k].point);
    Vec3 centre;
    const double r_eff = UniformPatchRadius(patch.data(), static_cast<int>(patch.size()), c0.normal, &centre);
    // the points' in-plane offsets from the centroid, and their mean length
    double mean = 0.0;
    for (Vec3& d : patch) {
      d -= centre;
      d -= c0.normal.dot(d) * c0.normal;
      mean += d.norm() / static_cast<double>(end - first);
    }
    const double shrink = r_eff > 0.0 && mean > 0.0 ? 1.0 - r_eff / mean : 0.0;
    for (size_t k = first; k < end; ++k) (*points)[k] = contacts[k].point - shrink * patch[k - first];
    first = end;
  }
}

}  // namespace contactsim
