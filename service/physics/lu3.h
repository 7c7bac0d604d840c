// x = A^-1 b for a 3 x 3 A by LU with partial pivoting (Golub and Van Loan,
// "Matrix Computations", 4th ed., algorithm 3.4.1), in the order of
// operations of Eigen 3.4's fixed-size PartialPivLU<Matrix3d>::solve: the
// pivot is the first largest |a_ik|, the multipliers are quotients, the
// trailing block takes a_ij - l_i u_j, and the triangular solves subtract a
// row's dot product (summed left to right) before dividing by the diagonal.
// The same bits as Eigen's, without its dispatch, permutation object and
// loops over runtime sizes: MidpointRotation (integrator.h) solves such a
// system in every fixed-point iteration of every dynamic body's rotation.
// A zero pivot is kept (Eigen leaves its column undivided); the quotient
// is then infinite or NaN, as Eigen's is.
#pragma once

#include <cmath>
#include <utility>

#include "service/physics/math.h"

namespace contactsim {

inline Vec3 SolveLu3(const Mat3& m, const Vec3& rhs) {
  double a[3][3] = {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
  double b[3] = {rhs.x(), rhs.y(), rhs.z()};
  for (int k = 0; k < 2; ++k) {
    int p = k;
    double best = std::abs(a[k][k]);
    for (int i = k + 1; i < 3; ++i) {
      const double v = std::abs(a[i][k]);
      if (v > best) best = v, p = i;
    }
    if (best != 0.0) {
      if (p != k) {
        for (int j = 0; j < 3; ++j) std::swap(a[k][j], a[p][j]);
      }
      for (int i = k + 1; i < 3; ++i) a[i][k] /= a[k][k];
    }
    for (int i = k + 1; i < 3; ++i) {
      for (int j = k + 1; j < 3; ++j) a[i][j] -= a[i][k] * a[k][j];
    }
    // the row transpositions, applied to b in order (Eigen's P b)
    std::swap(b[k], b[p]);
  }
  // L y = P b (unit diagonal), then U x = y
  b[1] -= a[1][0] * b[0];
  b[2] -= a[2][0] * b[0] + a[2][1] * b[1];
  b[2] /= a[2][2];
  b[1] -= a[1][2] * b[2];
  b[1] /= a[1][1];
  b[0] -= a[0][1] * b[1] + a[0][2] * b[2];
  b[0] /= a[0][0];
  return Vec3(b[0], b[1], b[2]);
}

}  // namespace contactsim
