// Tests of the penalty force laws and the restitution-to-damping relation.
#include "service/contact/penalty/penalty_force.h"

#include <gtest/gtest.h>

#include <cmath>

namespace contactsim {
namespace {

// Restitution of the no-pull linear spring-dashpot by direct integration:
// unit mass and stiffness, impact at speed 1, RK4 until the force
// x + 2 zeta x' reaches zero.
double IntegratedRestitution(double zeta) {
  const double h = 1e-5;
  double x = 0.0, v = 1.0;  // x: depth, v: penetration rate
  auto accel = [zeta](double x_, double v_) { return -(x_ + 2.0 * zeta * v_); };
  for (int i = 0; i < 10000000; ++i) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    x += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (x + 2.0 * zeta * v <= 0.0) return -v;
  }
  return 0.0;
}

// Verifies the closed form of the no-tension restitution against a direct
// integration, under, at and over critical damping.
TEST(PenaltyForce, NoTensionRestitutionMatchesIntegration) {
  // the integration stops within one 1e-5 step of the force's zero
  const double kTolerance = 1e-4;
  for (double zeta : {0.0, 0.05, 0.2155, 0.5, 0.7071, 0.9, 1.0, 1.5, 3.0}) {
    EXPECT_NEAR(NoTensionRestitution(zeta), IntegratedRestitution(zeta), kTolerance) << "zeta = " << zeta;
  }
}

// Verifies that the classic formula would overshoot: at the zeta it gives
// for e = 0.5, a dashpot that cannot pull rebounds with e = 0.55.
TEST(PenaltyForce, ClassicFormulaUnderdampsTheNoPullDashpot) {
  const double e = 0.5;
  const double zeta_classic = -std::log(e) / std::sqrt(M_PI * M_PI + std::log(e) * std::log(e));
  EXPECT_NEAR(NoTensionRestitution(zeta_classic), 0.550, 1e-3);
  EXPECT_GT(ZetaFromRestitution(e), zeta_classic);
}

// Verifies that ZetaFromRestitution inverts NoTensionRestitution, over
// and under critical damping, and stops at kMaxZeta.
TEST(PenaltyForce, ZetaFromRestitutionInvertsAndSaturates) {
  for (double e : {0.01, 0.05, 0.1, 0.15, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    EXPECT_NEAR(NoTensionRestitution(ZetaFromRestitution(e)), e, 1e-12) << e;
  }
  EXPECT_EQ(ZetaFromRestitution(1.0), 0.0);
  EXPECT_NEAR(ZetaFromRestitution(0.0), kMaxZeta, 1e-12);
  EXPECT_NEAR(NoTensionRestitution(1.0), std::exp(-2.0), 1e-12);
  // e = 0 rebounds with 0.0024 of the impact speed: 6e-6 of the drop height
  EXPECT_LT(NoTensionRestitution(kMaxZeta), 0.0025);
  // kd = 2 zeta sqrt(kp m)
  EXPECT_NEAR(DampingFromRestitution(0.5, 1e4, 4.0), 2.0 * ZetaFromRestitution(0.5) * 200.0, 1e-9);
}

// Verifies the laws' values, no pull, and their derivatives against central
// differences.
TEST(PenaltyForce, LawsPushNeverPullAndHaveTheirSlopes) {
  for (const char* model : {"linear", "hunt_crossley"}) {
    PenaltyParams p;
    p.model = model;
    p.kp = 1e5;
    const double damping = std::string(model) == "linear" ? 300.0 : 0.3;
    const double nc = 2.0, d = 2e-3, vn = -0.4;
    const NormalLaw law = EvaluateNormalLaw(p, d, vn, nc, damping);
    const double expected = std::string(model) == "linear" ? (p.kp * d - damping * vn) / nc
                                                           : p.kp * std::pow(d, 1.5) * (1.0 - 1.5 * damping * vn) / nc;
    EXPECT_NEAR(law.lambda0, expected, 1e-9 * expected) << model;
    const double step_d = 1e-7, step_v = 1e-5;
    const double dk = (EvaluateNormalLaw(p, d + step_d, vn, nc, damping).lambda0 -
                       EvaluateNormalLaw(p, d - step_d, vn, nc, damping).lambda0) / (2.0 * step_d);
    const double dc = -(EvaluateNormalLaw(p, d, vn + step_v, nc, damping).lambda0 -
                        EvaluateNormalLaw(p, d, vn - step_v, nc, damping).lambda0) / (2.0 * step_v);
    EXPECT_NEAR(law.k, dk, 1e-6 * law.k) << model;
    EXPECT_NEAR(law.c, dc, 1e-6 * law.c) << model;
    // a fast separation: the linear law's value goes negative (the callers
    // clamp it); Hunt-Crossley's damping factor would pull, so it is zero
    const NormalLaw fast = EvaluateNormalLaw(p, d, 100.0, nc, damping);
    if (std::string(model) == "linear") {
      EXPECT_LT(fast.lambda0, 0.0);
    } else {
      EXPECT_EQ(fast.lambda0, 0.0);
      EXPECT_EQ(fast.k, 0.0);
    }
    // apart: the linear law keeps its spring for the implicit prediction,
    // without damping; Hunt-Crossley is zero
    const NormalLaw apart = EvaluateNormalLaw(p, -1e-3, vn, nc, damping);
    EXPECT_LE(apart.lambda0, 0.0);
    EXPECT_EQ(apart.c, 0.0);
  }
}

// Verifies the Hunt-Crossley alpha of Flores et al. and its floors.
TEST(PenaltyForce, HuntCrossleyAlphaFollowsFlores) {
  EXPECT_NEAR(HuntCrossleyAlpha(0.5, 2.0), 16.0 * 0.5 / (15.0 * 0.5 * 2.0), 1e-12);
  EXPECT_EQ(HuntCrossleyAlpha(0.5, 0.0), HuntCrossleyAlpha(0.5, kMinImpactSpeed));
  EXPECT_EQ(HuntCrossleyAlpha(0.0, 1.0), HuntCrossleyAlpha(kMinHuntCrossleyRestitution, 1.0));
  EXPECT_EQ(HuntCrossleyAlpha(1.0, 1.0), 0.0);
}

}  // namespace
}  // namespace contactsim
