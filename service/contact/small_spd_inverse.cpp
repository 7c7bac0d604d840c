#include "service/contact/small_spd_inverse.h"

#include <cmath>

namespace contactsim {
namespace {

// Eigen factors a padded 4 x 4, so column j's update below the pivot is a
// matrix-vector product for j = 1 (its sum starts from 0) and a dot
// product for j = 2 (it starts from the first term); the padding's rows
// are zero there and add nothing.
template <int N>
bool Factor(const Eigen::Matrix4d& k, double (&l)[4][4]) {
  for (int j = 0; j < N; ++j) {
    double x = k(j, j);
    if (j > 0) {
      double squares = l[j][0] * l[j][0];
      for (int m = 1; m < j; ++m) squares += l[j][m] * l[j][m];
      x -= squares;
    }
    if (!(x > 0.0)) return false;
    l[j][j] = std::sqrt(x);
    for (int i = j + 1; i < N; ++i) {
      double v = k(i, j);
      if (j == 1) v -= 0.0 + l[i][0] * l[1][0];
      if (j == 2) v -= l[i][0] * l[2][0] + l[i][1] * l[2][1];
      l[i][j] = v / l[j][j];
    }
  }
  return true;
}

template <int N>
bool Inverse(const Eigen::Matrix4d& k, Eigen::Matrix4d* inv, double* pivots) {
  double l[4][4];
  if (!Factor<N>(k, l)) return false;
  double a[N];
  for (int i = 0; i < N; ++i) {
    pivots[i] = l[i][i];
    a[i] = 1.0 / l[i][i];
  }
#pragma GCC unroll 4
  for (int j = 0; j < N; ++j) {
    // L y = e_j, subtracting each term as it comes; y's entries above j
    // stay 0 and subtract (signed) zeros below it, which leave them as
    // they are, so the solve starts at j
    double y[N];
#pragma GCC unroll 4
    for (int i = 0; i < N; ++i) y[i] = 0.0;
    y[j] = a[j];
#pragma GCC unroll 4
    for (int r = j + 1; r < N; ++r) y[r] -= y[j] * l[r][j];
#pragma GCC unroll 4
    for (int i = j + 1; i < N; ++i) {
      y[i] *= a[i];
#pragma GCC unroll 4
      for (int r = i + 1; r < N; ++r) y[r] -= y[i] * l[r][i];
    }
    // L^T x = y, subtracting the sum
    double x[N];
#pragma GCC unroll 4
    for (int i = N - 1; i >= 0; --i) {
      double b = 0.0;
#pragma GCC unroll 4
      for (int s = i + 1; s < N; ++s) b += l[s][i] * x[s];
      x[i] = (y[i] - b) * a[i];
    }
    for (int i = 0; i < N; ++i) (*inv)(i, j) = x[i];
  }
  return true;
}

}  // namespace

bool SmallSpdInverse(const Eigen::Matrix4d& k, int n, Eigen::Matrix4d* inv, double* pivots) {
  switch (n) {
    case 2:
      return Inverse<2>(k, inv, pivots);
    case 3:
      return Inverse<3>(k, inv, pivots);
    case 4:
      return Inverse<4>(k, inv, pivots);
    default:
      return false;
  }
}

}  // namespace contactsim
