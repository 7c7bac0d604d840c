#include "service/contact/normal_block.h"

#include <algorithm>

#include "service/contact/small_spd_inverse.h"

namespace contactsim {
namespace {

// The unit c with J^T c = 0 for four points: sum c_i = 0 and sum c_i r_i
// parallel to n, the null vector of the 3 x 4 matrix [1; u; v] of the
// points' tangent coordinates, by cofactors; false when the points lie on a
// line (every cofactor vanishes).
bool FaceNullVector(const Vec3* points, const Vec3& t1, const Vec3& t2, Eigen::Vector4d* c) {
  double u[4], v[4];
  double extent = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Vec3 r = points[i] - points[0];
    u[i] = r.dot(t1);
    v[i] = r.dot(t2);
    extent = std::max(extent, u[i] * u[i] + v[i] * v[i]);
  }
  auto minor = [&](int i, int j, int k) { return (u[j] - u[i]) * (v[k] - v[i]) - (u[k] - u[i]) * (v[j] - v[i]); };
  *c = Eigen::Vector4d(minor(1, 2, 3), -minor(0, 2, 3), minor(0, 1, 3), -minor(0, 1, 2));
  const double norm = c->norm();
  if (!(norm > 1e-9 * extent)) return false;
  *c /= norm;
  return true;
}

// The inverse of the symmetric positive definite top-left `count` x
// `count` of `k` (its lower triangle) when well conditioned: L's diagonal
// spreads by less than 1e5, a smaller block's padding of the identity
// counting with pivots of 1 (small_spd_inverse.h). *inv is written only
// then, its other rows and columns zero.
bool InvertIfWellConditioned(const Eigen::Matrix4d& k, int count, Eigen::Matrix4d* inv) {
  Eigen::Matrix4d result = Eigen::Matrix4d::Zero();
  double d[kMaxNormalBlock];
  if (!SmallSpdInverse(k, count, &result, d)) return false;
  double lo = count < kMaxNormalBlock ? 1.0 : d[0];
  double hi = lo;
  for (int i = 0; i < count; ++i) {
    lo = std::min(lo, d[i]);
    hi = std::max(hi, d[i]);
  }
  if (!(lo > 1e-5 * hi)) return false;
  *inv = result;
  return true;
}

}  // namespace

bool InvertNormalBlockK(const Eigen::Matrix4d& k_in, int count, const Vec3* plane_points, const Vec3& t1,
                        const Vec3& t2, Eigen::Matrix4d* inv_k) {
  if (count < 2 || count > kMaxNormalBlock) return false;
  if (count < kMaxNormalBlock) return InvertIfWellConditioned(k_in, count, inv_k);
  // four points with one normal act on three velocities, so their K is
  // singular (see the header): straight to K^+, without first trying K's
  // own Cholesky factor (BENCHMARKS.md, "### lcp")
  Eigen::Vector4d c;
  if (!FaceNullVector(plane_points, t1, t2, &c)) return false;
  if (!InvertIfWellConditioned(k_in + c * c.transpose(), kMaxNormalBlock, inv_k)) return false;
  *inv_k -= c * c.transpose();
  return true;
}

bool InvertNormalBlock(const NormalBlockPoint* points, int count, double k_lin, const Vec3& t1, const Vec3& t2,
                       Eigen::Matrix4d* inv_k) {
  if (count < 2 || count > kMaxNormalBlock) return false;
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  Vec3 plane[kMaxNormalBlock];
  for (int i = 0; i < count; ++i) {
    plane[i] = points[i].ra;
    for (int j = 0; j < count; ++j) {
      k(i, j) = k_lin + points[i].ra_n.dot(points[j].ia_n) + points[i].rb_n.dot(points[j].ib_n);
    }
  }
  return InvertNormalBlockK(k, count, plane, t1, t2, inv_k);
}

}  // namespace contactsim
