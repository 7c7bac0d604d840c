// Closed-form separating-axis test of two boxes (see box_box_sat.h).
#include "service/collision/box_box_sat.h"

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

}  // namespace

SatResult FindBoxBoxSeparatingAxis(const RigidBody& a, const RigidBody& b, double early_out) {
  return FindBoxBoxSeparatingAxis(BoxPose(a), BoxPose(b), early_out);
}

SatResult FindBoxBoxSeparatingAxis(const BoxPose& a, const BoxPose& b, double early_out) {
  const Mat3& Ra = a.R;
  const Mat3& Rb = b.R;
  const Vec3& ha = a.h;
  const Vec3& hb = b.h;
  const Vec3 d = b.x - a.x;
  const Mat3 abs_c = (Ra.transpose() * Rb).cwiseAbs();  // |A_i . B_j|
  const Vec3 da = Ra.transpose() * d;
  const Vec3 db = Rb.transpose() * d;

  // faces of A, in topology order +x, -x, +y, -y, +z, -z: the support of B
  // along s A_i is s A_i . d - sum_j hb_j |A_i . B_j| from A's centre
  BestAxis face_a;
  for (int f = 0; f < 6; ++f) {
    const int i = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = s * da[i] - ha[i] - abs_c.row(i).dot(hb);
    if (face_a.Improves(sep)) face_a.separation = sep, face_a.i = f, face_a.sign = s;
    if (sep > early_out) return EarlyOutResult(FaceResult(face_a, SeparatingAxis::Kind::kFaceA, Ra));
  }
  // faces of B: outward normal s B_j, the axis from A to B is its opposite
  BestAxis face_b;
  for (int f = 0; f < 6; ++f) {
    const int j = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = -s * db[j] - hb[j] - abs_c.col(j).dot(ha);
    if (face_b.Improves(sep)) face_b.separation = sep, face_b.i = f, face_b.sign = -s;
    if (sep > early_out) return EarlyOutResult(FaceResult(face_b, SeparatingAxis::Kind::kFaceB, Rb));
  }
  // edge directions A_i x B_j, oriented from A to B; parallel pairs skipped
  BestAxis edges;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = Ra.col(i).cross(Rb.col(j));
      const double len = c.norm();
      if (len < kSatParallelSin) continue;
      Vec3 u = c / len;
      double ud = u.dot(d);
      if (ud < 0.0) u = -u, ud = -ud;
      double ra = 0.0, rb = 0.0;
      for (int k = 0; k < 3; ++k) {
        ra += ha[k] * std::abs(u.dot(Ra.col(k)));
        rb += hb[k] * std::abs(u.dot(Rb.col(k)));
      }
      const double sep = ud - ra - rb;
      if (edges.Improves(sep)) edges.separation = sep, edges.i = i, edges.j = j, edges.u = u;
      if (sep > early_out) return EarlyOutResult(EdgeResult(edges, Ra, Rb));
    }
  }
  return ChooseSeparatingAxis(FaceResult(face_a, SeparatingAxis::Kind::kFaceA, Ra),
                              FaceResult(face_b, SeparatingAxis::Kind::kFaceB, Rb), EdgeResult(edges, Ra, Rb));
}

}  // namespace contactsim
