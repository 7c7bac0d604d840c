#include "service/contact/barrier/barrier_potential.h"

#include <cmath>
#include <limits>

#include "service/physics/portable_math.h"

namespace contactsim {

double Barrier(double d, double d_hat) {
  if (d <= 0.0) return std::numeric_limits<double>::infinity();
  if (d >= d_hat) return 0.0;
  const double s = d - d_hat;
  return -s * s * portable::Log(d / d_hat);
}

double BarrierFirstDerivative(double d, double d_hat) {
  if (d <= 0.0 || d >= d_hat) return 0.0;
  const double s = d - d_hat;
  return -2.0 * s * portable::Log(d / d_hat) - s * s / d;
}

double BarrierSecondDerivative(double d, double d_hat) {
  if (d <= 0.0 || d >= d_hat) return 0.0;
  const double s = d - d_hat;
  return -2.0 * portable::Log(d / d_hat) - 4.0 * s / d + s * s / (d * d);
}

double FrictionF0(double y, double eps) {
  if (y >= eps) return y;
  return -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
}

double FrictionF1(double y, double eps) {
  if (y >= eps) return 1.0;
  return -y * y / (eps * eps) + 2.0 * y / eps;
}

double FrictionF1OverY(double y, double eps) {
  if (y >= eps) return 1.0 / y;
  return -y / (eps * eps) + 2.0 / eps;
}

}  // namespace contactsim
