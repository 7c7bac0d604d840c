// LU factorisation with partial pivoting of a small dense matrix stored row
// by row (Golub and Van Loan, "Matrix Computations", 4th ed., algorithm
// 3.4.1: Gaussian elimination with partial pivoting, the multipliers kept
// below the diagonal), and the solve with it for several right-hand sides.
// Plain loops over the matrix's own size: the joint tree solver's blocks are
// 5 to 24 rows, where a general library's blocked kernels cost several times
// the arithmetic in their dispatch and packing. The common sizes (5 to 8
// rows, 1 and 5 to 8 right-hand sides: a joint's rows, a body's velocity
// block) are passed as compile-time constants, so that their loops unroll.
#pragma once

#include <cmath>
#include <type_traits>
#include <utility>

namespace contactsim {

// a (n x n, row r at a + r n) := its L and U factors in place (unit lower L
// below the diagonal), rows swapped as pivots[k] (row k with row pivots[k],
// k = 0 .. n-1 in order). A zero pivot is left for the solve to divide by, as
// a singular matrix has no factors; the joint systems are regularised so that
// none is singular (joint_rows.h, kJointRegularisation).
template <typename Size>
inline void LuFactorOf(Size size, double* a, int* pivots) {
  const int n = size;
  for (int k = 0; k < n; ++k) {
    int p = k;
    double best = std::abs(a[k * n + k]);
    for (int i = k + 1; i < n; ++i) {
      const double v = std::abs(a[i * n + k]);
      if (v > best) best = v, p = i;
    }
    pivots[k] = p;
    if (p != k) {
#pragma GCC unroll 8
      for (int j = 0; j < n; ++j) std::swap(a[k * n + j], a[p * n + j]);
    }
    const double pivot = a[k * n + k];
    const double* row_k = a + k * n;
    for (int i = k + 1; i < n; ++i) {
      double* row_i = a + i * n;
      const double l = row_i[k] / pivot;
      row_i[k] = l;
#pragma GCC unroll 8
      for (int j = k + 1; j < n; ++j) row_i[j] -= l * row_k[j];
    }
  }
}

template <typename Size, typename Width>
inline void LuSolveOf(Size size, const double* lu, const int* pivots, double* b, Width width) {
  const int n = size, m = width;
  for (int k = 0; k < n; ++k) {
    if (pivots[k] == k) continue;
#pragma GCC unroll 8
    for (int j = 0; j < m; ++j) std::swap(b[k * m + j], b[pivots[k] * m + j]);
  }
  for (int i = 1; i < n; ++i) {  // L y = P b
    double* bi = b + i * m;
    for (int k = 0; k < i; ++k) {
      const double l = lu[i * n + k];
      const double* bk = b + k * m;
#pragma GCC unroll 8
      for (int j = 0; j < m; ++j) bi[j] -= l * bk[j];
    }
  }
  for (int i = n - 1; i >= 0; --i) {  // U x = y
    double* bi = b + i * m;
    for (int k = i + 1; k < n; ++k) {
      const double u = lu[i * n + k];
      const double* bk = b + k * m;
#pragma GCC unroll 8
      for (int j = 0; j < m; ++j) bi[j] -= u * bk[j];
    }
    const double d = lu[i * n + i];
#pragma GCC unroll 8
    for (int j = 0; j < m; ++j) bi[j] /= d;
  }
}

// Calls f(std::integral_constant<int, n>()) when n is one of Ns, else f(n).
template <int... Ns, typename F>
inline void WithSize(int n, F&& f) {
  const bool fixed = ((n == Ns ? (f(std::integral_constant<int, Ns>()), true) : false) || ...);
  if (!fixed) f(n);
}

inline void LuFactor(int n, double* a, int* pivots) {
  WithSize<5, 6, 7, 8>(n, [&](auto size) { LuFactorOf(size, a, pivots); });
}

// b (n x m, row r at b + r m) := A^-1 b for the factors of LuFactor.
inline void LuSolve(int n, const double* lu, const int* pivots, double* b, int m) {
  WithSize<5, 6, 7, 8>(n, [&](auto size) {
    WithSize<1, 5, 6, 7, 8>(m, [&](auto width) { LuSolveOf(size, lu, pivots, b, width); });
  });
}

}  // namespace contactsim
