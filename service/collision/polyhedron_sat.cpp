// Separating-axis test between convex polyhedra (see polyhedron_sat.h).
#include "service/collision/polyhedron_sat.h"

#include "service/collision/minkowski_edge_pairs.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace contactsim {
namespace {

// Edge pairs at least this many take the Gauss-map grid
// (minkowski_edge_pairs.h); fewer are cheaper tested one by one.
constexpr int kEdgeGridMinPairs = 1024;

// min over B of n.v - offset: the separation along outward face normal n of
// the other body whose support value is `offset`; *start is the descent's
// first vertex (MinProjection).
double FaceSeparation(const Vec3& n, double offset, const PosedPolyhedron& other, int* start) {
  return MinProjection(other, n, start) - offset;
}

double FaceSeparation(const Vec3& n, double offset, const PosedPolyhedron& other) {
  int start = 0;
  return FaceSeparation(n, offset, other, &start);
}

// Any edge axis dA x dB by projection, oriented from A to B by whichever sign
// separates more: for a cached axis, which may no longer be a Minkowski face.
bool EdgeSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, int ea, int eb,
                    Vec3* normal, double* separation) {
  const Vec3 c = a.edge_dirs[ea].cross(b.edge_dirs[eb]);
  const double len = c.norm();
  if (len < kSatParallelSin) return false;
  const Vec3 u = c / len;
  double lo_a, hi_a, lo_b, hi_b;
  ProjectPolyhedron(a, u, &lo_a, &hi_a);
  ProjectPolyhedron(b, u, &lo_b, &hi_b);
  const double sep_plus = lo_b - hi_a;   // B beyond A along +u
  const double sep_minus = lo_a - hi_b;  // B beyond A along -u
  if (sep_plus >= sep_minus) {
    *normal = u;
    *separation = sep_plus;
  } else {
    *normal = -u;
    *separation = sep_minus;
  }
  return true;
}

// Separation along the axis of a Minkowski-face edge pair: the axis is the
// face's outward normal, pointing away from A's centre, and the face plane
// passes through both edges, so one point of each gives it in O(1).
bool MinkowskiEdgeSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, int ea, int eb,
                             Vec3* normal, double* separation) {
  const Vec3 c = a.edge_dirs[ea].cross(b.edge_dirs[eb]);
  const double len = c.norm();
  if (len < kSatParallelSin) return false;
  const Vec3& pa = a.vertices[a.topology->edges[ea][0]];
  const Vec3& pb = b.vertices[b.topology->edges[eb][0]];
  Vec3 u = c / len;
  if (u.dot(pa - a.centre) < 0.0) u = -u;
  *normal = u;
  *separation = u.dot(pb - pa);
  return true;
}

// Depth threshold that a challenger must go below to replace a preferred axis
// of depth d (see polyhedron_sat.h).
double PreferenceThreshold(double d, double rel) {
  return d - std::min((1.0 - rel) * std::max(d, 0.0), kSatMaxBias) - kSatAbsTolerance;
}

}  // namespace

SatResult MakeSatResult(const SeparatingAxis& axis, const Vec3& normal, double separation) {
  SatResult r;
  r.axis = axis;
  r.normal = normal;
  r.separation = separation;
  r.max_separation = separation;
  r.max_normal = normal;
  return r;
}

SatResult EarlyOutResult(SatResult r) {
  r.max_separation = r.separation;
  r.max_normal = r.normal;
  return r;
}

bool AxisSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, const SeparatingAxis& axis,
                    Vec3* normal, double* separation) {
  switch (axis.kind) {
    case SeparatingAxis::Kind::kFaceA:
      if (axis.a < 0 || axis.a >= static_cast<int>(a.normals.size())) return false;
      *normal = a.normals[axis.a];
      *separation = FaceSeparation(a.normals[axis.a], a.offsets[axis.a], b);
      return true;
    case SeparatingAxis::Kind::kFaceB:
      if (axis.b < 0 || axis.b >= static_cast<int>(b.normals.size())) return false;
      *normal = -b.normals[axis.b];
      *separation = FaceSeparation(b.normals[axis.b], b.offsets[axis.b], a);
      return true;
    case SeparatingAxis::Kind::kEdges:
      if (axis.a < 0 || axis.a >= static_cast<int>(a.edge_dirs.size()) || axis.b < 0 ||
          axis.b >= static_cast<int>(b.edge_dirs.size())) {
        return false;
      }
      return EdgeSeparation(a, b, axis.a, axis.b, normal, separation);
    case SeparatingAxis::Kind::kNone:
      break;
  }
  return false;
}

namespace {

// The best face of A (into *face_a) and of B (into *face_b), in face order;
// true, with *early the result, at the first face that separates by more
// than early_out.
bool FaceQueries(const PosedPolyhedron& a, const PosedPolyhedron& b, double early_out, SatResult* face_a,
                 SatResult* face_b, SatResult* early) {
  // faces of A: outward normals point from A to B
  int start = 0;  // consecutive faces' minimisers are near: each descent starts at the last
  for (int f = 0; f < static_cast<int>(a.normals.size()); ++f) {
    const double sep = FaceSeparation(a.normals[f], a.offsets[f], b, &start);
    if (sep > face_a->separation) *face_a = MakeSatResult({SeparatingAxis::Kind::kFaceA, f, -1}, a.normals[f], sep);
    if (sep > early_out) return *early = EarlyOutResult(*face_a), true;
  }
  // faces of B: outward normals point from B to A
  start = 0;
  for (int f = 0; f < static_cast<int>(b.normals.size()); ++f) {
    const double sep = FaceSeparation(b.normals[f], b.offsets[f], a, &start);
    if (sep > face_b->separation) *face_b = MakeSatResult({SeparatingAxis::Kind::kFaceB, -1, f}, -b.normals[f], sep);
    if (sep > early_out) return *early = EarlyOutResult(*face_b), true;
  }
  return false;
}

// One edge pair's candidate: the Minkowski-face test on closed topologies
// (`tested`: already known to pass), projection on open ones.
bool EdgePairSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, int ea, int eb, bool tested,
                        Vec3* n, double* sep) {
  const std::array<int, 2>* fa = EdgeFaces(a, ea);
  const std::array<int, 2>* fb = EdgeFaces(b, eb);
  if (fa == nullptr || fb == nullptr) return EdgeSeparation(a, b, ea, eb, n, sep);  // open topology: project
  const auto& na = a.normals;
  const auto& nb = b.normals;
  if (!tested && !IsMinkowskiFace(na[(*fa)[0]], na[(*fa)[1]], -nb[(*fb)[0]], -nb[(*fb)[1]])) return false;
  return MinkowskiEdgeSeparation(a, b, ea, eb, n, sep);
}

// The best edge pair (into *edges), in (edge of A, edge of B) order; true,
// with *early the result, at the first that separates by more than early_out.
// Large closed pairs visit only the pairs that form Minkowski faces
// (MinkowskiEdgePairs: the same pairs in the same order as the double loop).
bool EdgeQuery(const PosedPolyhedron& a, const PosedPolyhedron& b, double early_out, EdgePairScratch* scratch,
               SatResult* edges, SatResult* early) {
  const int edges_a = static_cast<int>(a.edge_dirs.size());
  const int edges_b = static_cast<int>(b.edge_dirs.size());
  const auto visit = [&](int ea, int eb, bool tested) {
    Vec3 n;
    double sep;
    if (!EdgePairSeparation(a, b, ea, eb, tested, &n, &sep)) return false;
    if (sep > edges->separation) *edges = MakeSatResult({SeparatingAxis::Kind::kEdges, ea, eb}, n, sep);
    if (sep > early_out) return *early = EarlyOutResult(*edges), true;
    return false;
  };
  if (static_cast<int64_t>(edges_a) * edges_b >= kEdgeGridMinPairs && HasClosedTopology(a) &&
      HasClosedTopology(b)) {
    EdgePairScratch local;
    EdgePairScratch& s = scratch != nullptr ? *scratch : local;
    MinkowskiEdgePairs(a, b, &s);
    for (const int64_t key : s.pairs) {
      if (visit(static_cast<int>(key / edges_b), static_cast<int>(key % edges_b), true)) return true;
    }
    return false;
  }
  // small closed pairs (a box on a triangle's prism) read the Gauss-map
  // test from tables; open topologies test each pair
  GaussArcTable table;
  const bool tabled = table.Build(a, b);
  for (int ea = 0; ea < edges_a; ++ea) {
    for (int eb = 0; eb < edges_b; ++eb) {
      if (tabled && !table.IsMinkowskiFace(ea, eb)) continue;
      if (visit(ea, eb, tabled)) return true;
    }
  }
  return false;
}

}  // namespace

SatResult FindSeparatingAxis(const PosedPolyhedron& a, const PosedPolyhedron& b, double early_out,
                             EdgePairScratch* scratch) {
  const double kNoAxis = -std::numeric_limits<double>::infinity();
  SatResult face_a, face_b, edges, early;
  face_a.separation = face_b.separation = edges.separation = kNoAxis;
  if (FaceQueries(a, b, early_out, &face_a, &face_b, &early)) return early;
  // one edge of each, where they form a Minkowski face; parallel pairs skipped
  if (EdgeQuery(a, b, early_out, scratch, &edges, &early)) return early;
  return ChooseSeparatingAxis(face_a, face_b, edges);
}

double EdgeChoiceSeparation(const SatResult& faces) {
  // -d_edge < threshold(d_face) with d = -separation; negation is exact
  return -PreferenceThreshold(-faces.separation, kSatEdgeRelTolerance);
}

SatResult ChooseSeparatingAxis(const SatResult& face_a, const SatResult& face_b, const SatResult& edges) {
  // the unbiased maximum (first of equals: faces of A, faces of B, edges)
  const SatResult* max = &face_a;
  if (face_b.separation > max->separation) max = &face_b;
  if (edges.separation > max->separation) max = &edges;
  const double max_separation = max->separation;
  const Vec3 max_normal = max->normal;
  // prefer faces of A, then faces of B, then edges (depth d = -separation)
  SatResult best = face_a;
  if (-face_b.separation < PreferenceThreshold(-best.separation, kSatFaceRelTolerance)) best = face_b;
  if (edges.axis.kind != SeparatingAxis::Kind::kNone && edges.separation > EdgeChoiceSeparation(best)) best = edges;
  best.max_separation = max_separation;
  best.max_normal = max_normal;
  return best;
}

}  // namespace contactsim
