// Closed-form separating-axis test of two boxes (see box_box_sat.h).
#include "service/collision/box_box_sat.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "service/collision/posed_polyhedron.h"

namespace contactsim {
namespace {

// Edge index in UnitBoxTopology() of the edge along axis `dir` whose other
// two coordinates are those of vertex `corner` (index bits x, y, z).
class BoxEdgeTable {
 public:
  BoxEdgeTable() {
    const auto& edges = UnitBoxTopology().edges;
    for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
      const int v0 = edges[e][0], v1 = edges[e][1];
      const int bit = v0 ^ v1;
      const int dir = bit == 1 ? 0 : bit == 2 ? 1 : 2;
      index_[dir][v0 & ~bit] = e;
    }
  }
  int operator()(int dir, int corner) const { return index_[dir][corner & ~(1 << dir)]; }

 private:
  std::array<std::array<int, 8>, 3> index_{};
};

// Corner (index bits) of the box with frame axes R's columns that lies
// farthest along u.
int SupportCorner(const Mat3& R, const Vec3& u) {
  int corner = 0;
  for (int k = 0; k < 3; ++k) {
    if (u.dot(R.col(k)) > 0.0) corner |= 1 << k;
  }
  return corner;
}

// The best candidate of one family of axes so far: only its place is kept
// in the loops, and its SatResult is built once (building one per
// improvement, with its four vectors, was a tenth of the test).
struct BestAxis {
  double separation = -std::numeric_limits<double>::infinity();
  int i = -1, j = -1;  // face (0-5), or edge directions of A and B (0-2)
  double sign = 1.0;   // of the face's axis
  Vec3 u = Vec3::UnitZ();  // the edge axis, oriented from A to B
  bool Improves(double sep) const { return sep > separation; }
};

SatResult FaceResult(const BestAxis& best, SeparatingAxis::Kind kind, const Mat3& R) {
  if (best.i < 0) {
    SatResult none;
    none.separation = best.separation;
    return none;
  }
  const int f = best.i;
  const SeparatingAxis axis = kind == SeparatingAxis::Kind::kFaceA ? SeparatingAxis{kind, f, -1}
                                                                    : SeparatingAxis{kind, -1, f};
  return MakeSatResult(axis, Vec3(best.sign * R.col(f / 2)), best.separation);
}

SatResult EdgeResult(const BestAxis& best, const Mat3& Ra, const Mat3& Rb) {
  static const BoxEdgeTable kEdgeIndex;
  if (best.i < 0) {
    SatResult none;
    none.separation = best.separation;
    return none;
  }
  // A's edge farthest along u, B's edge farthest along -u
  const int ea = kEdgeIndex(best.i, SupportCorner(Ra, best.u));
  const int eb = kEdgeIndex(best.j, SupportCorner(Rb, -best.u));
  return MakeSatResult({SeparatingAxis::Kind::kEdges, ea, eb}, best.u, best.separation);
}

// The boxes' relative frame, shared by the three families of axes.
struct BoxPair {
  const BoxPose& a;
  const BoxPose& b;
  Vec3 d;      // m, world: B's centre from A's
  Mat3 abs_c;  // |A_i . B_j|
  Vec3 da, db;  // m: d in A's and in B's frame
  BoxPair(const BoxPose& pa, const BoxPose& pb)
      : a(pa), b(pb), d(pb.x - pa.x), abs_c((pa.R.transpose() * pb.R).cwiseAbs()), da(pa.R.transpose() * d),
        db(pb.R.transpose() * d) {}
};

// The best face of A and of B; returns false with *early set when one
// separates by more than early_out.
bool FaceAxes(const BoxPair& p, double early_out, SatResult* face_a_result, SatResult* face_b_result,
              SatResult* early) {
  const Vec3& ha = p.a.h;
  const Vec3& hb = p.b.h;
  // faces of A, in topology order +x, -x, +y, -y, +z, -z: the support of B
  // along s A_i is s A_i . d - sum_j hb_j |A_i . B_j| from A's centre
  BestAxis face_a;
  for (int f = 0; f < 6; ++f) {
    const int i = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = s * p.da[i] - ha[i] - p.abs_c.row(i).dot(hb);
    if (face_a.Improves(sep)) face_a.separation = sep, face_a.i = f, face_a.sign = s;
    if (sep > early_out) return *early = EarlyOutResult(FaceResult(face_a, SeparatingAxis::Kind::kFaceA, p.a.R)), false;
  }
  // faces of B: outward normal s B_j, the axis from A to B is its opposite
  BestAxis face_b;
  for (int f = 0; f < 6; ++f) {
    const int j = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = -s * p.db[j] - hb[j] - p.abs_c.col(j).dot(ha);
    if (face_b.Improves(sep)) face_b.separation = sep, face_b.i = f, face_b.sign = -s;
    if (sep > early_out) return *early = EarlyOutResult(FaceResult(face_b, SeparatingAxis::Kind::kFaceB, p.b.R)), false;
  }
  *face_a_result = FaceResult(face_a, SeparatingAxis::Kind::kFaceA, p.a.R);
  *face_b_result = FaceResult(face_b, SeparatingAxis::Kind::kFaceB, p.b.R);
  return true;
}

// The best edge pair; returns false with *early set when one separates by
// more than early_out.
bool EdgeAxes(const BoxPair& p, double early_out, SatResult* edges_result, SatResult* early) {
  const Mat3& Ra = p.a.R;
  const Mat3& Rb = p.b.R;
  // edge directions A_i x B_j, oriented from A to B; parallel pairs skipped
  BestAxis edges;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = Ra.col(i).cross(Rb.col(j));
      const double len = c.norm();
      if (len < kSatParallelSin) continue;
      Vec3 u = c / len;
      double ud = u.dot(p.d);
      if (ud < 0.0) u = -u, ud = -ud;
      double ra = 0.0, rb = 0.0;
      for (int k = 0; k < 3; ++k) {
        ra += p.a.h[k] * std::abs(u.dot(Ra.col(k)));
        rb += p.b.h[k] * std::abs(u.dot(Rb.col(k)));
      }
      const double sep = ud - ra - rb;
      if (edges.Improves(sep)) edges.separation = sep, edges.i = i, edges.j = j, edges.u = u;
      if (sep > early_out) return *early = EarlyOutResult(EdgeResult(edges, Ra, Rb)), false;
    }
  }
  *edges_result = EdgeResult(edges, Ra, Rb);
  return true;
}

// Whether some edge pair's separation, as EdgeAxes computes it, may exceed
// `limit` (m). Each pair's separation in closed form from the entries of
// C = Ra^T Rb (ODE's dBoxBox; Gottschalk, Lin and Manocha's table): for
// c = A_i x B_j, with i1, i2 and j1, j2 the other two indices in cyclic
// order, c . A_i1 = -C_i2j, c . A_i2 = C_i1j, c . B_j1 = C_ij2,
// c . B_j2 = -C_ij1, |c| = sqrt(C_i1j^2 + C_i2j^2), and
//   sep |c| = |c . d| - ha_i1 |C_i2j| - ha_i2 |C_i1j| - hb_j1 |C_ij2| - hb_j2 |C_ij1|,
// a tenth of the loop's products. The two differ by round-off, a few
// 1e-16 of the boxes' size over |c| for unit quaternions (the integrator
// and MakeOrientation normalise every orientation); kScreenRelTolerance
// allows 1e-7 of it, so that a pair this says cannot exceed the limit does
// not. A pair is left out as parallel only at half the loop's cut-off.
bool SomeEdgeMayExceed(const BoxPair& p, double limit) {
  constexpr double kScreenRelTolerance = 1e-7;
  const Mat3 C = p.a.R.transpose() * p.b.R;
  const Vec3& ha = p.a.h;
  const Vec3& hb = p.b.h;
  const double size = p.da.cwiseAbs().sum() + ha.sum() + hb.sum();
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double len = std::sqrt(C(i1, j) * C(i1, j) + C(i2, j) * C(i2, j));
      // EdgeAxes skips it too: its |c| is within round-off of len
      if (len < 0.5 * kSatParallelSin) continue;
      const double cd = C(i1, j) * p.da[i2] - C(i2, j) * p.da[i1];
      const double sep_len = std::abs(cd) - ha[i1] * std::abs(C(i2, j)) - ha[i2] * std::abs(C(i1, j)) -
                             hb[j1] * std::abs(C(i, j2)) - hb[j2] * std::abs(C(i, j1));
      if ((sep_len + kScreenRelTolerance * size) / len >= limit) return true;
    }
  }
  return false;
}

}  // namespace

SatResult FindBoxBoxSeparatingAxis(const RigidBody& a, const RigidBody& b, double early_out) {
  return FindBoxBoxSeparatingAxis(BoxPose(a), BoxPose(b), early_out);
}

SatResult FindBoxBoxSeparatingAxis(const BoxPose& a, const BoxPose& b, double early_out) {
  const BoxPair pair(a, b);
  SatResult face_a, face_b, edges, early;
  if (!FaceAxes(pair, early_out, &face_a, &face_b, &early)) return early;
  if (!EdgeAxes(pair, early_out, &edges, &early)) return early;
  return ChooseSeparatingAxis(face_a, face_b, edges);
}

SatResult FindBoxBoxContactAxis(const BoxPose& a, const BoxPose& b, double early_out) {
  const BoxPair pair(a, b);
  SatResult face_a, face_b, edges, early;
  if (!FaceAxes(pair, early_out, &face_a, &face_b, &early)) return early;
  // the faces' choice stands unless an edge pair beats it or stops the test
  SatResult no_edges;
  no_edges.separation = -std::numeric_limits<double>::infinity();
  const SatResult faces = ChooseSeparatingAxis(face_a, face_b, no_edges);
  if (!SomeEdgeMayExceed(pair, std::min(EdgeChoiceSeparation(faces), early_out))) return faces;
  if (!EdgeAxes(pair, early_out, &edges, &early)) return early;
  return ChooseSeparatingAxis(face_a, face_b, edges);
}

}  // namespace contactsim
