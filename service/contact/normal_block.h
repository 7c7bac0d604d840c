// The normal rows of up to four contact points of one body pair with one
// normal, solved as a block: the rows are coupled through the bodies'
// rotations, so one Gauss-Seidel sweep over them gives the first point swept
// more than its share. Solving them together (Catto's block solver for two
// points, Box2D) gives each its share:
//   K = J M^-1 J^T of the block's normal rows,
//   K_ij = 1/m_A + 1/m_B + (r_Ai x n) . I_A^-1 (r_Aj x n) + (r_Bi x n) . I_B^-1 (r_Bj x n),
//   dlambda = -K^-1 (v_n + bias), kept when every accumulated impulse stays
//   >= 0 (otherwise the caller sweeps the points one by one).
// Two points (an edge, a lying capsule) and three get K^-1. The four points
// of a face act on three velocities (v_n and two tilts), so their K is
// singular along c, the points' affine dependency in the face's plane
// (sum c_i = 0, sum c_i r_i parallel to n; + - + - on a square): they get
// K^+ = (K + c c^T)^-1 - c c^T, the least-norm increment, which adds nothing
// along c, so a symmetric face gets four equal impulses whatever order its
// points come in (docs/methods/soft.md, "Manifold block").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/physics/math.h"

namespace contactsim {

constexpr int kMaxNormalBlock = 4;

// One point of a block: its lever arm on A and the normal row's angular
// Jacobians and responses on both bodies.
struct NormalBlockPoint {
  Vec3 ra;          // m, contact point minus A's centre of mass (its in-plane part places the point)
  Vec3 ra_n, rb_n;  // r_A x n, r_B x n
  Vec3 ia_n, ib_n;  // I_A^-1 (r_A x n), I_B^-1 (r_B x n) (zero for a static body)
};

// Consecutive points of one body pair, up to four (the narrowphase emits a
// pair's points together); `block` when K is (pseudo-)inverted in inv_k.
struct NormalBlock {
  int first = 0;  // points [first, first + count)
  int count = 0;
  bool block = false;
  Eigen::Matrix4d inv_k = Eigen::Matrix4d::Zero();
};

// Groups `points` (anything with body indices a and b, and a unit normal
// `normal`) into blocks of one body pair and one normal; the caller
// inverts each block's K. The normal splits a compound body's points,
// whose child pairs touch along different normals (shape.h).
template <class Point>
void GroupNormalBlocks(const std::vector<Point>& points, Vec3 Point::*normal, std::vector<NormalBlock>* blocks) {
  blocks->clear();
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    NormalBlock* last = blocks->empty() ? nullptr : &blocks->back();
    if (last != nullptr && last->count < kMaxNormalBlock && points[last->first].a == points[k].a &&
        points[last->first].b == points[k].b &&
        (points[last->first].*normal).dot(points[k].*normal) >= 1.0 - 1e-9) {
      ++last->count;
    } else {
      blocks->push_back(NormalBlock{k, 1, false, Eigen::Matrix4d::Zero()});
    }
  }
}

// K^-1 (or K^+ for four coplanar points) of `count` points (2 to 4) sharing
// the unit normal n with tangents t1, t2, and the pair's linear part
// k_lin = 1/m_A + 1/m_B; unused rows and columns of a smaller block are
// left zero. False when no block applies: fewer than two points, or K too
// badly conditioned (three points on a line, a point repeated).
bool InvertNormalBlock(const NormalBlockPoint* points, int count, double k_lin, const Vec3& t1, const Vec3& t2,
                       Eigen::Matrix4d* inv_k);

// The same from K itself (the lower triangle of its first `count` rows and
// columns; the rest is ignored) and a point per row that places it in the face's plane up to an
// affine map (the lever arm r, or r x n, whose tangent coordinates are r's
// turned by 90 degrees): for solvers that hold each row's J and M^-1 J^T.
bool InvertNormalBlockK(const Eigen::Matrix4d& k, int count, const Vec3* plane_points, const Vec3& t1,
                        const Vec3& t2, Eigen::Matrix4d* inv_k);

}  // namespace contactsim
