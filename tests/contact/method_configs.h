// Every registered contact method as a test parameter, taken from the
// registry (ContactMethodNames()) rather than a hand list, so a method added
// to the registry joins every suite built on it; lcp runs once per solver
// (pgs and lemke), since its two solvers answer differently, and soft once
// per precision (double, and float over SIMD lanes).
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/contact_method_registry.h"
#include "service/contact/method_support.h"

namespace contactsim {
namespace testing {

// One configuration of a method: its registry name, the parameters set on
// top of its defaults, and a label for test names and tables.
struct MethodConfig {
  std::string method;
  ParamMap params;
  std::string label;
};

inline void PrintTo(const MethodConfig& c, std::ostream* os) { *os << c.label; }

// Every registered method with its defaults, lcp with each solver.
inline std::vector<MethodConfig> EveryMethodConfig() {
  std::vector<MethodConfig> configs;
  for (const std::string& name : ContactMethodNames()) {
    if (name == "lcp") {
      configs.push_back({name, {{"solver", "pgs"}}, "lcp_pgs"});
      configs.push_back({name, {{"solver", "lemke"}}, "lcp_lemke"});
    } else if (name == "soft") {
      // the float path (precision=float) is a configuration of its own: it
      // answers in single precision, with its own bundles' order
      configs.push_back({name, {}, name});
      configs.push_back({name, {{"precision", "float"}}, "soft_float"});
    } else {
      configs.push_back({name, {}, name});
    }
  }
  return configs;
}

// The configurations that simulate a jointed world each in their own way:
// soft's float path hands any world with joints to soft's double path
// (docs/methods/soft.md, "Float path"), so the joint suites would run soft twice.
inline std::vector<MethodConfig> JointedWorldConfigs() {
  std::vector<MethodConfig> configs;
  for (MethodConfig& c : EveryMethodConfig()) {
    if (c.label != "soft_float") configs.push_back(std::move(c));
  }
  return configs;
}

// The method's contract, from its registry row.
inline const MethodContract& ContractOf(const MethodConfig& config) {
  return FindContactMethod(config.method)->contract;
}

// True when the method refuses `world` (method_support.h), which it must do
// exactly when its contract lacks what the world holds (`promised` false):
// the refusal is FAILED_PRECONDITION naming `what` ("joints",
// "restitution"), and the scenario ends there, verified, instead of
// stepping a world the method would get wrong.
inline bool RefusedByContract(const MethodConfig& config, const World& world, bool promised, const char* what) {
  const Status support = CheckMethodSupports(config.method, world);
  EXPECT_EQ(support.ok(), promised) << config.label << ": " << support.message();
  if (support.ok()) return false;
  EXPECT_EQ(support.code(), StatusCode::kFailedPrecondition) << config.label;
  EXPECT_NE(support.message().find(what), std::string::npos) << support.message();
  std::printf("%-10s refused: %s\n", config.label.c_str(), support.message().c_str());
  return true;
}

// The label as a gtest parameter name.
inline std::string ConfigName(const ::testing::TestParamInfo<MethodConfig>& info) { return info.param.label; }

}  // namespace testing
}  // namespace contactsim
