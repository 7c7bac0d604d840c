#include "service/contact/barrier/affine_body.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace contactsim {

Vec12 AffineFromPose(const Vec3& p, const Mat3& A) {
  Vec12 q;
  q << p, A.row(0).transpose(), A.row(1).transpose(), A.row(2).transpose();
  return q;
}

Vec3 AffinePosition(const Vec12& q) { return q.head<3>(); }

Mat3 AffineMatrix(const Vec12& q) {
  Mat3 A;
  A.row(0) = q.segment<3>(3).transpose();
  A.row(1) = q.segment<3>(6).transpose();
  A.row(2) = q.segment<3>(9).transpose();
  return A;
}

Vec3 AffinePoint(const Vec12& q, const Vec3& X) {
  return Vec3(q(0) + q.segment<3>(3).dot(X), q(1) + q.segment<3>(6).dot(X), q(2) + q.segment<3>(9).dot(X));
}

Vec12 AffineJacobianT(const Vec3& X, const Vec3& v) {
  Vec12 g;
  g << v, v.x() * X, v.y() * X, v.z() * X;
  return g;
}

Vec12 AffineMass::Times(const Vec12& v) const {
  Vec12 out;
  out << m * v.head<3>(), S * v.segment<3>(3), S * v.segment<3>(6), S * v.segment<3>(9);
  return out;
}

Vec12 AffineMass::Solve(const Vec12& f) const {
  const Mat3 inv = S.inverse();
  Vec12 out;
  out << f.head<3>() / m, inv * f.segment<3>(3), inv * f.segment<3>(6), inv * f.segment<3>(9);
  return out;
}

Mat12 AffineMass::Matrix() const {
  Mat12 M = Mat12::Zero();
  M.block<3, 3>(0, 0) = m * Mat3::Identity();
  for (int k = 1; k < 4; ++k) M.block<3, 3>(3 * k, 3 * k) = S;
  return M;
}

AffineMass AffineMassOf(const RigidBody& body) {
  AffineMass mass;
  mass.m = body.mass;
  mass.S = 0.5 * body.inertia_body.trace() * Mat3::Identity() - body.inertia_body;
  return mass;
}

void RigidToAffine(const RigidBody& body, Vec12* q, Vec12* qdot) {
  const Mat3 R = body.Rotation();
  *q = AffineFromPose(body.x, R);
  *qdot = AffineFromPose(body.LinearVelocity(), Skew(body.AngularVelocity()) * R);
}

Mat3 NearestRotation(const Mat3& A) {
  Eigen::JacobiSVD<Mat3> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU();
  const Mat3 V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(2) = -U.col(2);
  return U * V.transpose();
}

double OrthogonalityEnergy(const Vec12& q, double k) {
  const Mat3 A = AffineMatrix(q);
  return k * (A * A.transpose() - Mat3::Identity()).squaredNorm();
}

void OrthogonalityDerivatives(const Vec12& q, double k, Vec12* gradient, Mat12* hessian) {
  const Mat3 A = AffineMatrix(q);
  const Mat3 C = A * A.transpose() - Mat3::Identity();  // C_ij = a_i . a_j - delta_ij
  gradient->setZero();
  Eigen::Matrix<double, 9, 9> H = Eigen::Matrix<double, 9, 9>::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec3 ai = A.row(i).transpose();
    Vec3 g = Vec3::Zero();
    for (int j = 0; j < 3; ++j) g += C(i, j) * A.row(j).transpose();
    gradient->segment<3>(3 + 3 * i) = 4.0 * k * g;
    for (int l = 0; l < 3; ++l) {
      const Vec3 al = A.row(l).transpose();
      Mat3 block;
      if (l == i) {
        // d/da_i of 4 sum_j C_ij a_j = 4 (sum_{j != i} a_j a_j^T + 2 a_i a_i^T + C_ii I)
        block = C(i, i) * Mat3::Identity() + 2.0 * ai * ai.transpose();
        for (int j = 0; j < 3; ++j) {
          if (j != i) block += A.row(j).transpose() * A.row(j);
        }
      } else {
        block = C(i, l) * Mat3::Identity() + al * ai.transpose();
      }
      H.block<3, 3>(3 * i, 3 * l) = 4.0 * k * block;
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(0.5 * (H + H.transpose()));
  const Eigen::Matrix<double, 9, 1> values = eig.eigenvalues().cwiseMax(0.0);
  hessian->setZero();
  hessian->block<9, 9>(3, 3) = eig.eigenvectors() * values.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace contactsim
