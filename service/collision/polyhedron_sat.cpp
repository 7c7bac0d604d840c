// Separating-axis test between convex polyhedra (see polyhedron_sat.h).
#include "service/collision/polyhedron_sat.h"

#include <algorithm>
#include <limits>

namespace contactsim {
namespace {

// Edge pairs with |dA x dB| below this are skipped: sin(angle) < 1e-6 gives an
// ill-conditioned axis, and near-parallel edges are separated by face axes.
constexpr double kParallelSin = 1e-6;

// min over B of n.v - offset: the separation along outward face normal n of
// the other body whose support value is `offset`.
double FaceSeparation(const Vec3& n, double offset, const PosedPolyhedron& other) {
  double min_p = std::numeric_limits<double>::infinity();
  for (const Vec3& v : other.vertices) min_p = std::min(min_p, n.dot(v));
  return min_p - offset;
}

// Edge axis dA x dB, oriented from A to B by whichever sign separates more
// (both orientations are candidates; the projections decide).
bool EdgeSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, int ea, int eb,
                    Vec3* normal, double* separation) {
  const Vec3 c = a.edge_dirs[ea].cross(b.edge_dirs[eb]);
  const double len = c.norm();
  if (len < kParallelSin) return false;
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

// Depth threshold that a challenger must go below to replace a preferred axis
// of depth d (see polyhedron_sat.h).
double PreferenceThreshold(double d, double rel) { return std::min(rel * d, d) - kSatAbsTolerance; }

SatResult MakeResult(const SeparatingAxis& axis, const Vec3& normal, double separation) {
  SatResult r;
  r.axis = axis;
  r.normal = normal;
  r.separation = separation;
  r.max_separation = separation;
  return r;
}

// An early-out result: its axis separates more than asked, which is all that
// is known of the maximum.
SatResult WithMax(SatResult r) {
  r.max_separation = r.separation;
  return r;
}

}  // namespace

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

SatResult FindSeparatingAxis(const PosedPolyhedron& a, const PosedPolyhedron& b, double early_out) {
  const double kNoAxis = -std::numeric_limits<double>::infinity();
  SatResult face_a, face_b, edges;
  face_a.separation = face_b.separation = edges.separation = kNoAxis;

  // faces of A: outward normals point from A to B
  for (int f = 0; f < static_cast<int>(a.normals.size()); ++f) {
    const double sep = FaceSeparation(a.normals[f], a.offsets[f], b);
    if (sep > face_a.separation) face_a = MakeResult({SeparatingAxis::Kind::kFaceA, f, -1}, a.normals[f], sep);
    if (sep > early_out) return WithMax(face_a);
  }
  // faces of B: outward normals point from B to A
  for (int f = 0; f < static_cast<int>(b.normals.size()); ++f) {
    const double sep = FaceSeparation(b.normals[f], b.offsets[f], a);
    if (sep > face_b.separation) face_b = MakeResult({SeparatingAxis::Kind::kFaceB, -1, f}, -b.normals[f], sep);
    if (sep > early_out) return WithMax(face_b);
  }
  // one edge of each, skipping parallel pairs
  for (int ea : a.edge_axes) {
    for (int eb : b.edge_axes) {
      Vec3 n;
      double sep;
      if (!EdgeSeparation(a, b, ea, eb, &n, &sep)) continue;
      if (sep > edges.separation) edges = MakeResult({SeparatingAxis::Kind::kEdges, ea, eb}, n, sep);
      if (sep > early_out) return WithMax(edges);
    }
  }

  // prefer faces of A, then faces of B, then edges (depth d = -separation)
  const double max_separation = std::max({face_a.separation, face_b.separation, edges.separation});
  SatResult best = face_a;
  if (-face_b.separation < PreferenceThreshold(-best.separation, kSatFaceRelTolerance)) best = face_b;
  if (edges.axis.kind != SeparatingAxis::Kind::kNone &&
      -edges.separation < PreferenceThreshold(-best.separation, kSatEdgeRelTolerance)) {
    best = edges;
  }
  best.max_separation = max_separation;
  return best;
}

}  // namespace contactsim
