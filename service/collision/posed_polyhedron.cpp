// Posing boxes and hulls as polyhedra (see posed_polyhedron.h).
#include "service/collision/posed_polyhedron.h"

#include <algorithm>
#include <limits>

namespace contactsim {
namespace {

ConvexHull MakeUnitBox() {
  ConvexHull box;
  for (int i = 0; i < 8; ++i) {
    box.vertices.emplace_back((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
  }
  // loops counter-clockwise seen from outside: (v1 - v0) x (v2 - v1) is outward
  const int loops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                           {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  const Vec3 normals[6] = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitY(),
                           -Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ()};
  for (int f = 0; f < 6; ++f) {
    ConvexHull::Face face;
    face.normal = normals[f];
    face.offset = 1.0;
    face.vertices.assign(loops[f], loops[f] + 4);
    box.faces.push_back(face);
  }
  box.edges = {{0, 1}, {0, 2}, {0, 4}, {2, 3}, {4, 5}, {6, 7},
               {1, 3}, {4, 6}, {5, 7}, {1, 5}, {2, 6}, {3, 7}};
  ConnectEdgeFaces(&box);
  return box;
}

}  // namespace

const ConvexHull& UnitBoxTopology() {
  static const ConvexHull kUnitBox = MakeUnitBox();
  return kUnitBox;
}

bool PosePolyhedron(const RigidBody& body, PosedPolyhedron* out) {
  Vec3 scale = Vec3::Ones();
  if (body.shape.type == ShapeType::kBox) {
    out->topology = &UnitBoxTopology();
    scale = body.shape.half_extents;
  } else if (body.shape.type == ShapeType::kConvex && body.shape.hull != nullptr) {
    out->topology = body.shape.hull.get();
  } else {
    return false;
  }
  const ConvexHull& topo = *out->topology;
  const Mat3 R = body.Rotation();
  out->centre = body.x;

  out->vertices.resize(topo.vertices.size());
  for (size_t i = 0; i < topo.vertices.size(); ++i) {
    out->vertices[i] = PosedVertex(R, scale, body.x, topo.vertices[i]);
  }
  if (body.shape.type == ShapeType::kBox) {
    // the unit box's face normals and edges lie along the frame axes: face
    // 2i + s has normal (-1)^s R e_i and offset n . x + h_i, and the edges
    // of topo.edges run from the lower vertex index to the higher, along +R e_i
    out->normals.resize(6);
    out->offsets.resize(6);
    for (int f = 0; f < 6; ++f) {
      out->normals[f] = BoxFaceNormal(R, f);
      out->offsets[f] = BoxFaceOffset(out->normals[f], body.x, scale, f);
    }
    out->edge_dirs.resize(topo.edges.size());
    for (size_t e = 0; e < topo.edges.size(); ++e) {
      const int bit = topo.edges[e][0] ^ topo.edges[e][1];
      out->edge_dirs[e] = R.col(bit == 1 ? 0 : bit == 2 ? 1 : 2);
    }
    return true;
  }
  // a plane n . p = o maps under p' = S p to (S^-1 n) . p' = o
  const Vec3 inv_scale = scale.cwiseInverse();
  out->normals.resize(topo.faces.size());
  out->offsets.resize(topo.faces.size());
  for (size_t f = 0; f < topo.faces.size(); ++f) {
    const Vec3 n = R * topo.faces[f].normal.cwiseProduct(inv_scale).normalized();
    out->normals[f] = n;
    out->offsets[f] = n.dot(out->vertices[topo.faces[f].vertices.front()]);
  }
  out->edge_dirs.resize(topo.edges.size());
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    out->edge_dirs[e] = (out->vertices[topo.edges[e][1]] - out->vertices[topo.edges[e][0]]).normalized();
  }
  return true;
}

void ProjectPolyhedron(const PosedPolyhedron& poly, const Vec3& axis, double* lo, double* hi) {
  double min_v = std::numeric_limits<double>::infinity();
  double max_v = -min_v;
  for (const Vec3& v : poly.vertices) {
    const double p = axis.dot(v);
    if (p < min_v) min_v = p;
    if (p > max_v) max_v = p;
  }
  *lo = min_v;
  *hi = max_v;
}

double MinProjection(const PosedPolyhedron& poly, const Vec3& n, int* start) {
  const int count = static_cast<int>(poly.vertices.size());
  const std::vector<int>& first = poly.topology->neighbour_start;
  if (count < kDescentMinVertices || static_cast<int>(first.size()) != count + 1) {
    double min_p = std::numeric_limits<double>::infinity();
    for (const Vec3& v : poly.vertices) min_p = std::min(min_p, n.dot(v));
    return min_p;
  }
  double min_p;
  *start = DescendVertexGraph(*poly.topology, *start, [&](int i) { return n.dot(poly.vertices[i]); }, &min_p);
  return min_p;
}

int SupportVertex(const PosedPolyhedron& poly, const Vec3& direction) {
  int best = 0;
  double best_p = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.vertices.size(); ++i) {
    const double p = direction.dot(poly.vertices[i]);
    if (p > best_p) {
      best_p = p;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace contactsim
