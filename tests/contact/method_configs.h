// Every registered contact method as a test parameter, taken from the
// registry (ContactMethodNames()) rather than a hand list, so a method added
// to the registry joins every suite built on it; lcp runs once per solver
// (pgs and lemke), since its two solvers answer differently.
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"

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
    } else {
      configs.push_back({name, {}, name});
    }
  }
  return configs;
}

// The label as a gtest parameter name.
inline std::string ConfigName(const ::testing::TestParamInfo<MethodConfig>& info) { return info.param.label; }

}  // namespace testing
}  // namespace contactsim
