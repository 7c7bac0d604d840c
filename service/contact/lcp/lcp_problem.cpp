#include "service/contact/lcp/lcp_problem.h"

#include <algorithm>
#include <cmath>

namespace contactsim {

const char* LcpOutcomeName(LcpOutcome outcome) {
  switch (outcome) {
    case LcpOutcome::kSolved: return "solved";
    case LcpOutcome::kRayTermination: return "ray termination";
    case LcpOutcome::kPivotLimit: return "pivot limit";
    case LcpOutcome::kSingular: return "singular";
  }
  return "unknown";
}

double LcpError(const MatX& M, const VecX& q, const VecX& z) {
  const VecX w = M * z + q;
  double err = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    err = std::max({err, -z[i], -w[i], std::abs(z[i] * w[i])});
  }
  return err;
}

}  // namespace contactsim
