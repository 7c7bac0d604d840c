// Convex hull of a point cloud as polygon faces, edges and mass properties.
//
// Quickhull (quickhull.h) gives triangles; here adjacent triangles whose
// vertices lie within the tolerance of a common plane are merged into one
// polygon (a box has 6 quads, not 12 triangles), vertices that only sit on
// the straight part of an edge are dropped, and the hull is recentred at the
// centre of mass of the solid (polyhedron_integrals.h).
#include "service/physics/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include "service/physics/polyhedron_integrals.h"
#include "service/physics/quickhull.h"

namespace contactsim {
namespace {

using Triangle = std::array<int, 3>;

int64_t EdgeKey(int a, int b) { return (static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b); }

// Groups of edge-adjacent triangles lying in one plane (within tol), found by
// flooding from each unassigned triangle in order, against the seed's plane.
std::vector<int> GroupCoplanar(const std::vector<Vec3>& p, const std::vector<Triangle>& tris, double tol,
                               const std::unordered_map<int64_t, int>& edge_tri) {
  std::vector<int> group(tris.size(), -1);
  int groups = 0;
  for (int seed = 0; seed < static_cast<int>(tris.size()); ++seed) {
    if (group[seed] >= 0) continue;
    const Triangle& s = tris[seed];
    const Vec3 n = (p[s[1]] - p[s[0]]).cross(p[s[2]] - p[s[0]]).normalized();
    const double offset = n.dot(p[s[0]]);
    std::vector<int> queue = {seed};
    group[seed] = groups;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const Triangle& t = tris[queue[q]];
      for (int k = 0; k < 3; ++k) {
        const auto twin = edge_tri.find(EdgeKey(t[(k + 1) % 3], t[k]));
        if (twin == edge_tri.end() || group[twin->second] >= 0) continue;
        const Triangle& u = tris[twin->second];
        bool in_plane = true;
        for (int i : u) in_plane = in_plane && std::abs(n.dot(p[i]) - offset) <= tol;
        if (!in_plane) continue;
        group[twin->second] = groups;
        queue.push_back(twin->second);
      }
    }
    ++groups;
  }
  return group;
}

// Boundary loop of one group (its triangles `members`): its directed edges
// whose twin lies outside the group, chained head to tail. Counter-clockwise
// from outside, as the triangles are.
std::vector<int> BoundaryLoop(const std::vector<Triangle>& tris, const std::vector<int>& group, int g,
                              const std::vector<int>& members, const std::unordered_map<int64_t, int>& edge_tri) {
  std::map<int, int> next;
  for (int t : members) {
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      const auto twin = edge_tri.find(EdgeKey(b, a));
      if (twin == edge_tri.end() || group[twin->second] != g) next[a] = b;
    }
  }
  std::vector<int> loop;
  if (next.empty()) return loop;
  int v = next.begin()->first;
  do {
    loop.push_back(v);
    v = next[v];
  } while (v != loop.front() && loop.size() <= next.size());
  return loop;
}

bool IsCollinearIn(const std::vector<Vec3>& p, const std::vector<int>& loop, std::size_t i, double tol) {
  const std::size_t n = loop.size();
  const Vec3& a = p[loop[(i + n - 1) % n]];
  const Vec3& b = p[loop[(i + 1) % n]];
  const Vec3 axis = b - a;
  const double len = axis.norm();
  if (len <= tol) return true;
  return (p[loop[i]] - a).cross(axis).norm() / len <= tol;
}

// Newell's method: the area-weighted normal of a planar polygon, robust to
// collinear runs of vertices.
Vec3 NewellNormal(const std::vector<Vec3>& v, const std::vector<int>& loop) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) {
    n += v[loop[i]].cross(v[loop[(i + 1) % loop.size()]]);
  }
  return n.normalized();
}

}  // namespace

Status BuildConvexHull(const std::vector<Vec3>& points, std::shared_ptr<const ConvexHull>* hull,
                       Vec3* centroid_out) {
  if (points.size() < 4) {
    return Status::InvalidArgument("convex hull needs at least 4 points, got " + std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!IsFinite(points[i])) {
      std::ostringstream msg;
      msg << "point " << i << " is not finite: (" << points[i].x() << ", " << points[i].y() << ", "
          << points[i].z() << ")";
      return Status::InvalidArgument(msg.str());
    }
  }
  const double tol = HullTolerance(points);

  std::vector<Triangle> tris;
  Status status = Quickhull(points, tol, &tris);
  if (!status.ok()) return status;

  // merge coplanar triangles into polygon loops
  std::unordered_map<int64_t, int> edge_tri;
  for (int t = 0; t < static_cast<int>(tris.size()); ++t) {
    for (int k = 0; k < 3; ++k) edge_tri[EdgeKey(tris[t][k], tris[t][(k + 1) % 3])] = t;
  }
  const std::vector<int> group = GroupCoplanar(points, tris, tol, edge_tri);
  const int groups = group.empty() ? 0 : *std::max_element(group.begin(), group.end()) + 1;
  // each group's triangles, so that a loop looks at its own alone
  std::vector<std::vector<int>> members(groups);
  for (int t = 0; t < static_cast<int>(tris.size()); ++t) members[group[t]].push_back(t);
  std::vector<std::vector<int>> loops(groups);
  for (int g = 0; g < groups; ++g) loops[g] = BoundaryLoop(tris, group, g, members[g], edge_tri);

  // a vertex on the straight part of a hull edge is collinear in both faces
  // that share it; drop it only when it is collinear in every face, so that
  // neighbouring loops stay consistent
  std::map<int, bool> removable;
  for (const std::vector<int>& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const bool collinear = IsCollinearIn(points, loop, i, tol);
      auto it = removable.find(loop[i]);
      if (it == removable.end()) {
        removable[loop[i]] = collinear;
      } else {
        it->second = it->second && collinear;
      }
    }
  }

  // keep the referenced vertices, in input order (deterministic numbering)
  std::vector<int> new_index(points.size(), -1);
  auto out = std::make_shared<ConvexHull>();
  for (const auto& entry : removable) {
    if (entry.second) continue;
    new_index[entry.first] = static_cast<int>(out->vertices.size());
    out->vertices.push_back(points[entry.first]);
  }
  for (const std::vector<int>& loop : loops) {
    ConvexHull::Face face;
    for (int v : loop) {
      if (new_index[v] >= 0) face.vertices.push_back(new_index[v]);
    }
    if (face.vertices.size() < 3) continue;
    out->faces.push_back(std::move(face));
  }

  // recentre at the centre of mass of the solid
  const Vec3 centroid = ComputePolyhedronIntegrals(*out).centroid;
  for (Vec3& v : out->vertices) v -= centroid;
  for (ConvexHull::Face& face : out->faces) {
    face.normal = NewellNormal(out->vertices, face.vertices);
    double offset = 0.0;
    for (int v : face.vertices) offset += face.normal.dot(out->vertices[v]);
    face.offset = offset / static_cast<double>(face.vertices.size());
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      const int a = face.vertices[i], b = face.vertices[(i + 1) % face.vertices.size()];
      if (a < b) out->edges.push_back({a, b});
    }
  }
  std::sort(out->edges.begin(), out->edges.end());
  ConnectEdgeFaces(out.get());
  if (centroid_out != nullptr) *centroid_out = centroid;
  *hull = std::move(out);
  return Status::Ok();
}

void ConnectEdgeFaces(ConvexHull* hull) {
  // directed edges of the loops, sorted, so each edge's two sides are found
  // by binary search
  std::vector<std::pair<int64_t, int>> sides;  // (directed edge key, face)
  for (std::size_t f = 0; f < hull->faces.size(); ++f) {
    const std::vector<int>& loop = hull->faces[f].vertices;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      sides.emplace_back(EdgeKey(loop[k], loop[(k + 1) % loop.size()]), static_cast<int>(f));
    }
  }
  std::sort(sides.begin(), sides.end());
  const auto face_of = [&](int u, int v) {
    const auto it = std::lower_bound(sides.begin(), sides.end(), std::make_pair(EdgeKey(u, v), -1));
    return it != sides.end() && it->first == EdgeKey(u, v) ? it->second : -1;
  };
  hull->edge_faces.resize(hull->edges.size());
  for (std::size_t e = 0; e < hull->edges.size(); ++e) {
    const int u = hull->edges[e][0], v = hull->edges[e][1];
    hull->edge_faces[e] = {face_of(u, v), face_of(v, u)};
  }
  // the vertex graph: each edge counted at both ends, then placed
  const int n = static_cast<int>(hull->vertices.size());
  hull->neighbour_start.assign(n + 1, 0);
  for (const auto& e : hull->edges) ++hull->neighbour_start[e[0] + 1], ++hull->neighbour_start[e[1] + 1];
  for (int v = 0; v < n; ++v) hull->neighbour_start[v + 1] += hull->neighbour_start[v];
  hull->neighbours.resize(hull->neighbour_start[n]);
  std::vector<int> fill(hull->neighbour_start.begin(), hull->neighbour_start.end() - 1);
  for (const auto& e : hull->edges) {
    hull->neighbours[fill[e[0]]++] = e[1];
    hull->neighbours[fill[e[1]]++] = e[0];
  }
}

double ConvexHullVolume(const ConvexHull& hull) { return ComputePolyhedronIntegrals(hull).volume; }

MassProperties ConvexHullMassProperties(const ConvexHull& hull, double density) {
  const PolyhedronIntegrals integrals = ComputePolyhedronIntegrals(hull);
  MassProperties props;
  props.mass = density * integrals.volume;
  // I = rho (tr(C) 1 - C), C the second moment about the centre of mass
  const Mat3& c = integrals.second_moment;
  props.inertia = density * (c.trace() * Mat3::Identity() - c);
  return props;
}

}  // namespace contactsim
