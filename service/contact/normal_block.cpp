#include "service/contact/normal_block.h"

#include <Eigen/Cholesky>
#include <algorithm>

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

// The inverse of a symmetric positive definite `k` when well conditioned.
bool InvertIfWellConditioned(const Eigen::Matrix4d& k, Eigen::Matrix4d* inv) {
  const Eigen::LLT<Eigen::Matrix4d> llt(k);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector4d d = llt.matrixLLT().diagonal();
  if (!(d.minCoeff() > 1e-5 * d.maxCoeff())) return false;
  *inv = llt.solve(Eigen::Matrix4d::Identity());
  return true;
}

}  // namespace

bool InvertNormalBlockK(const Eigen::Matrix4d& k_in, int count, const Vec3* plane_points, const Vec3& t1,
                        const Vec3& t2, Eigen::Matrix4d* inv_k) {
  if (count < 2 || count > kMaxNormalBlock) return false;
  // a smaller block fills K's unused diagonal with 1 (identity rows)
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  k.topLeftCorner(count, count) = k_in.topLeftCorner(count, count);
  if (count < kMaxNormalBlock) {
    if (!InvertIfWellConditioned(k, inv_k)) return false;
    for (int i = count; i < kMaxNormalBlock; ++i) {
      inv_k->row(i).setZero();
      inv_k->col(i).setZero();
    }
    return true;
  }
  // four points with one normal act on three velocities, so their K is
  // singular (see the header): straight to K^+, without first trying K's
  // own Cholesky factor (BENCHMARKS.md, "### lcp")
  Eigen::Vector4d c;
  if (!FaceNullVector(plane_points, t1, t2, &c)) return false;
  if (!InvertIfWellConditioned(k + c * c.transpose(), inv_k)) return false;
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
