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

}  // namespace

SatResult FindBoxBoxSeparatingAxis(const RigidBody& a, const RigidBody& b, double early_out) {
  static const BoxEdgeTable kEdgeIndex;
  const Mat3 Ra = a.Rotation();
  const Mat3 Rb = b.Rotation();
  const Vec3& ha = a.shape.half_extents;
  const Vec3& hb = b.shape.half_extents;
  const Vec3 d = b.x - a.x;
  const Mat3 abs_c = (Ra.transpose() * Rb).cwiseAbs();  // |A_i . B_j|
  const Vec3 da = Ra.transpose() * d;
  const Vec3 db = Rb.transpose() * d;

  const double kNoAxis = -std::numeric_limits<double>::infinity();
  SatResult face_a, face_b, edges;
  face_a.separation = face_b.separation = edges.separation = kNoAxis;

  // faces of A, in topology order +x, -x, +y, -y, +z, -z: the support of B
  // along s A_i is s A_i . d - sum_j hb_j |A_i . B_j| from A's centre
  for (int f = 0; f < 6; ++f) {
    const int i = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = s * da[i] - ha[i] - abs_c.row(i).dot(hb);
    if (sep > face_a.separation) {
      face_a = MakeSatResult({SeparatingAxis::Kind::kFaceA, f, -1}, Vec3(s * Ra.col(i)), sep);
    }
    if (sep > early_out) return EarlyOutResult(face_a);
  }
  // faces of B: outward normal s B_j, the axis from A to B is its opposite
  for (int f = 0; f < 6; ++f) {
    const int j = f / 2;
    const double s = f % 2 == 0 ? 1.0 : -1.0;
    const double sep = -s * db[j] - hb[j] - abs_c.col(j).dot(ha);
    if (sep > face_b.separation) {
      face_b = MakeSatResult({SeparatingAxis::Kind::kFaceB, -1, f}, Vec3(-s * Rb.col(j)), sep);
    }
    if (sep > early_out) return EarlyOutResult(face_b);
  }
  // edge directions A_i x B_j, oriented from A to B; parallel pairs skipped
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
      if (sep > edges.separation) {
        // A's edge farthest along u, B's edge farthest along -u
        const int ea = kEdgeIndex(i, SupportCorner(Ra, u));
        const int eb = kEdgeIndex(j, SupportCorner(Rb, -u));
        edges = MakeSatResult({SeparatingAxis::Kind::kEdges, ea, eb}, u, sep);
      }
      if (sep > early_out) return EarlyOutResult(edges);
    }
  }
  return ChooseSeparatingAxis(face_a, face_b, edges);
}

}  // namespace contactsim
