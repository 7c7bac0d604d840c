// The one table of tolerances for the mechanics scenarios that every
// registered contact method runs (tests/contact/mechanics_*_test.cpp),
// mirrored in docs/physics.md, "Every method against mechanics". Each entry
// is the bound the method meets on every case of the scenario with a margin
// over what it measured; where a method misses the analytic answer by more,
// the case is listed in kKnownMisses with its measurement instead of
// widening the bound, and the suite skips it saying "known miss".
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

namespace contactsim {
namespace testing {

struct ScenarioTolerances {
  const char* label;        // MethodConfig::label (tests/contact/method_configs.h)
  double bounce;            // |apex / h - e^2|, first rebound of a dropped sphere
  double slide;             // relative error of the stopping distance v0^2 / (2 mu g)
  double incline_hold;      // m moved in 2 s on a slope with tan(theta) < mu
  double incline_slide;     // relative error of a t^2 / 2, a = g (sin - mu cos)
  double roll;              // relative error of a = 5/7 g sin(theta), and of omega r / v = 1
  double tip_stand;         // rad, tilt of a box below its tipping angle
  double stack_height;      // m, change of the top cube's height over 10 s
  double stack_drift;       // m, largest sideways displacement of a cube over 10 s
  double stack8_seconds;    // s, the 8-stack's horizon: 10, shorter where a run would pass ~60 s
  double stack20_seconds;   // s, the 20-stack's horizon, likewise
  double pendulum;          // relative error of the small-angle period
  double cradle;            // |v_last / v0 - 1| and |v_other| / v0 after the strike
  double rotation;          // relative drift of |L| and of the kinetic energy, 10 s free
  double resting_force;     // relative error of the summed normal force against m g
};

// clang-format off
inline constexpr ScenarioTolerances kScenarioTolerances[] = {
  // label        bounce slide  hold   inc.sl roll   tip    st.h    st.drift pend   cradle rot    force
  {"impulse",    0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  10, 10,   0.01,  0.05,  1e-6,  0.01},
  {"penalty",    0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  10, 10,   0.01,  0.05,  1e-6,  0.01},
  {"xpbd",       0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  10, 10,   0.01,  0.05,  1e-6,  0.01},
  {"lcp_pgs",    0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  10, 10,   0.01,  0.05,  1e-6,  0.01},
  {"lcp_lemke",  0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  5, 0.2,   0.01,  0.05,  1e-6,  0.01},
  {"barrier",    0.02,  0.02,  1e-3,  0.03,  0.015, 0.02,  1e-3,   1e-4,  10, 10,   0.01,  0.05,  1e-6,  0.01},
};
// clang-format on

// A case a method is known to miss: its measurement and why, as in
// docs/physics.md. `case_id` is the name the test gives the case.
struct KnownMiss {
  const char* label;
  const char* case_id;
  const char* why;
};

inline constexpr KnownMiss kKnownMisses[] = {
    {"", "", ""},  // placeholder: the list is filled from measurements
};

inline const ScenarioTolerances& TolerancesOf(const std::string& label) {
  for (const ScenarioTolerances& t : kScenarioTolerances) {
    if (label == t.label) return t;
  }
  ADD_FAILURE() << "no tolerances for method " << label << " in scenario_tolerances.h";
  static const ScenarioTolerances kNone{};
  return kNone;
}

inline const KnownMiss* FindKnownMiss(const std::string& label, const std::string& case_id) {
  for (const KnownMiss& m : kKnownMisses) {
    if (label == m.label && case_id == m.case_id) return &m;
  }
  return nullptr;
}

}  // namespace testing
}  // namespace contactsim

// Expects |measured - expected| <= tol for the case `case_id` of the method
// labelled `label`. A case in kKnownMisses that misses is skipped with its
// measurement, so the suite stays green and the miss stays visible; one
// that passes fails, so a fixed miss leaves the list.
#define EXPECT_MECHANICS(label, case_id, measured, expected, tol)                                              \
  do {                                                                                                         \
    const double measured_ = (measured), expected_ = (expected), tol_ = (tol);                                 \
    const bool within_ = std::abs(measured_ - expected_) <= tol_;                                              \
    const ::contactsim::testing::KnownMiss* miss_ = ::contactsim::testing::FindKnownMiss(label, case_id);      \
    if (miss_ != nullptr && !within_) {                                                                        \
      GTEST_SKIP() << "known miss: " << (label) << " " << (case_id) << " measured " << measured_ << " vs "     \
                   << expected_ << " (tolerance " << tol_ << "): " << miss_->why;                              \
    }                                                                                                          \
    EXPECT_TRUE(miss_ == nullptr) << (label) << " " << (case_id)                                               \
                                  << " is listed in kKnownMisses but is within tolerance now: remove it";      \
    EXPECT_NEAR(measured_, expected_, tol_) << (label) << " " << (case_id);                                    \
  } while (0)
