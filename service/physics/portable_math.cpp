#include "service/physics/portable_math.h"

#include <cmath>
#include <limits>

namespace contactsim {
namespace portable {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// pi/2 in three parts of 33 bits each (the last rounded): n * kPio2_1 and
// n * kPio2_2 are exact for |n| < 2^20
constexpr double kPio2_1 = 0x1.921fb54400000p+0;
constexpr double kPio2_2 = 0x1.0b4611a600000p-34;
constexpr double kPio2_3 = 0x1.3198a2e037073p-69;
constexpr double k2OverPi = 0x1.45f306dc9c883p-1;
// pi/2, pi/6 and pi as a double and the rest
constexpr double kPio2Hi = 0x1.921fb54442d18p+0, kPio2Lo = 0x1.1a62633145c07p-54;
constexpr double kPi6Hi = 0x1.0c152382d7366p-1, kPi6Lo = -0x1.ee6913347c2a6p-55;
constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;
constexpr double kSqrt3 = 0x1.bb67ae8584caap+0;
constexpr double kTanPi12 = 0x1.126145e9ecd56p-2;  // tan(pi/12) = 2 - sqrt(3)
// ln 2 in a part of 42 bits (k * kLn2Hi exact for |k| < 2^11) and the rest
constexpr double kLn2Hi = 0x1.62e42fefa3800p-1, kLn2Lo = 0x1.ef35793c76730p-45;
constexpr double kInvLn2 = 0x1.71547652b82fep+0;
constexpr double kSqrtHalf = 0x1.6a09e667f3bcdp-1;

// Horner's rule, c[0] + z (c[1] + z (...)).
template <int N>
double Horner(const double (&c)[N], double z) {
  double p = c[N - 1];
  for (int i = N - 2; i >= 0; --i) p = c[i] + z * p;
  return p;
}

// (-1)^j / (2j + 1)!, j = 1..9: sin r - r for |r| <= pi/4 below 1e-19 relative
constexpr double kSin[] = {-0x1.5555555555555p-3, 0x1.1111111111111p-7,  -0x1.a01a01a01a01ap-13,
                           0x1.71de3a556c734p-19, -0x1.ae64567f544e4p-26, 0x1.6124613a86d09p-33,
                           -0x1.ae7f3e733b81fp-41, 0x1.952c77030ad4ap-49, -0x1.2f49b46814157p-57};
// (-1)^j / (2j)!, j = 1..9
constexpr double kCos[] = {-0x1.0000000000000p-1, 0x1.5555555555555p-5,  -0x1.6c16c16c16c17p-10,
                           0x1.a01a01a01a01ap-16, -0x1.27e4fb7789f5cp-22, 0x1.1eed8eff8d898p-29,
                           -0x1.93974a8c07c9dp-37, 0x1.ae7f3e733b81fp-45, -0x1.6827863b97d97p-53};
// 1 / j!, j = 2..14: exp r for |r| <= ln2 / 2
constexpr double kExp[] = {0x1.0000000000000p-1, 0x1.5555555555555p-3, 0x1.5555555555555p-5,
                           0x1.1111111111111p-7, 0x1.6c16c16c16c17p-10, 0x1.a01a01a01a01ap-13,
                           0x1.a01a01a01a01ap-16, 0x1.71de3a556c734p-19, 0x1.27e4fb7789f5cp-22,
                           0x1.ae64567f544e4p-26, 0x1.1eed8eff8d898p-29, 0x1.6124613a86d09p-33,
                           0x1.93974a8c07c9dp-37};
// 1 / (2j + 1), j = 1..12: atanh s = s (1 + z / 3 + z^2 / 5 + ...), z = s^2 <= 0.0295
constexpr double kAtanh[] = {0x1.5555555555555p-2, 0x1.999999999999ap-3, 0x1.2492492492492p-3,
                             0x1.c71c71c71c71cp-4, 0x1.745d1745d1746p-4, 0x1.3b13b13b13b14p-4,
                             0x1.1111111111111p-4, 0x1.e1e1e1e1e1e1ep-5, 0x1.af286bca1af28p-5,
                             0x1.8618618618618p-5, 0x1.642c8590b2164p-5, 0x1.47ae147ae147bp-5};
// (-1)^j / (2j + 1), j = 1..17: atan u for |u| <= tan(pi/12), z = u^2 <= 0.0718
constexpr double kAtan[] = {-0x1.5555555555555p-2, 0x1.999999999999ap-3,  -0x1.2492492492492p-3,
                            0x1.c71c71c71c71cp-4,  -0x1.745d1745d1746p-4, 0x1.3b13b13b13b14p-4,
                            -0x1.1111111111111p-4, 0x1.e1e1e1e1e1e1ep-5,  -0x1.af286bca1af28p-5,
                            0x1.8618618618618p-5,  -0x1.642c8590b2164p-5, 0x1.47ae147ae147bp-5,
                            -0x1.2f684bda12f68p-5, 0x1.1a7b9611a7b96p-5,  -0x1.0842108421084p-5,
                            0x1.f07c1f07c1f08p-6,  -0x1.d41d41d41d41dp-6};

double SinKernel(double r) {  // |r| <= pi/4 (a little more after rounding)
  const double z = r * r;
  return r + r * z * Horner(kSin, z);
}

double CosKernel(double r) {
  const double z = r * r;
  return 1.0 + z * Horner(kCos, z);
}

// r = x - n pi/2 in [-pi/4, pi/4] and the quadrant n mod 4 (Cody-Waite).
double ReduceByHalfPi(double x, int* quadrant) {
  if (std::abs(x) <= 0.7853981633974483) {  // pi/4 rounded down
    *quadrant = 0;
    return x;
  }
  const double n = std::nearbyint(x * k2OverPi);
  *quadrant = static_cast<int>(std::fmod(n, 4.0)) & 3;  // fmod is exact; & 3 maps -1..-3 to 3..1
  return ((x - n * kPio2_1) - n * kPio2_2) - n * kPio2_3;
}

// atan x for x >= 0 (+inf included).
double AtanNonNegative(double x) {
  const bool inverted = x > 1.0;  // atan x = pi/2 - atan(1/x)
  const double t = inverted ? 1.0 / x : x;
  double a;
  if (t > kTanPi12) {  // atan t = pi/6 + atan((sqrt3 t - 1) / (t + sqrt3))
    const double u = (kSqrt3 * t - 1.0) / (t + kSqrt3);
    a = kPi6Hi + (u + u * (u * u) * Horner(kAtan, u * u) + kPi6Lo);
  } else {
    a = t + t * (t * t) * Horner(kAtan, t * t);
  }
  return inverted ? kPio2Hi - (a - kPio2Lo) : a;
}

}  // namespace

double Sin(double x) {
  if (!std::isfinite(x)) return kNaN;
  int q;
  const double r = ReduceByHalfPi(x, &q);
  switch (q) {
    case 0: return SinKernel(r);
    case 1: return CosKernel(r);
    case 2: return -SinKernel(r);
    default: return -CosKernel(r);
  }
}

double Cos(double x) {
  if (!std::isfinite(x)) return kNaN;
  int q;
  const double r = ReduceByHalfPi(x, &q);
  switch (q) {
    case 0: return CosKernel(r);
    case 1: return -SinKernel(r);
    case 2: return -CosKernel(r);
    default: return SinKernel(r);
  }
}

double Exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return kInf;  // ln(DBL_MAX)
  if (x < -745.2) return 0.0;             // below half the smallest subnormal
  // x = k ln2 + r, |r| <= ln2 / 2; e^x = 2^k e^r
  const double k = std::nearbyint(x * kInvLn2);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  const double er = 1.0 + (r + r * r * Horner(kExp, r));
  return std::ldexp(er, static_cast<int>(k));
}

double Log(double x) {
  if (std::isnan(x) || x == kInf) return x;
  if (x < 0.0) return kNaN;
  if (x == 0.0) return -kInf;
  // x = m 2^k, m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(s), s = (m - 1) / (m + 1)
  int k;
  double m = std::frexp(x, &k);
  if (m < kSqrtHalf) {
    m *= 2.0;
    --k;
  }
  const double f = m - 1.0;  // exact
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double ln_m = 2.0 * s + 2.0 * s * (z * Horner(kAtanh, z));
  return k * kLn2Hi + (ln_m + k * kLn2Lo);
}

double Pow(double x, double y) {
  if (std::isnan(x) || std::isnan(y) || x < 0.0) return kNaN;
  if (y == 0.0) return 1.0;
  if (x == 0.0) return y > 0.0 ? 0.0 : kInf;
  return Exp(y * Log(x));
}

double Atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (y == 0.0 || std::isinf(x)) {
    if (std::isinf(x) && std::isinf(y)) {
      return std::copysign(x > 0.0 ? 0.5 * kPio2Hi : 1.5 * kPio2Hi, y);  // +-pi/4, +-3pi/4
    }
    // on the x axis (or infinitely far along it): +-0 ahead, +-pi behind
    return std::copysign(std::signbit(x) ? kPiHi : 0.0, y);
  }
  if (x == 0.0 || std::isinf(y)) return std::copysign(kPio2Hi, y);
  const double a = AtanNonNegative(std::abs(y / x));  // y / x may round to 0 or inf: atan is flat there
  const double angle = x > 0.0 ? a : kPiHi - (a - kPiLo);
  return std::copysign(angle, y);
}

double Asin(double x) {
  if (!(std::abs(x) <= 1.0)) return kNaN;
  return Atan2(x, std::sqrt((1.0 - x) * (1.0 + x)));
}

}  // namespace portable
}  // namespace contactsim
