#include "service/contact/joints/joint_mass_ratio.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "service/contact/union_find.h"

namespace contactsim {

bool JointMassRatioAtLeast(const World& world, double ratio) {
  if (ratio <= 0.0 || world.joints().empty()) return false;
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  for (const Joint& j : world.joints()) {
    const int a = world.IndexOf(j.body_a), b = world.IndexOf(j.body_b);
    if (a >= 0 && b >= 0 && bodies[a].IsDynamic() && bodies[b].IsDynamic()) sets.Join(a, b);
  }
  std::vector<double> lightest(n, 0.0), heaviest(n, std::numeric_limits<double>::infinity());  // inverse masses
  for (int i = 0; i < n; ++i) {
    if (!bodies[i].IsDynamic()) continue;
    const int root = sets.Root(i);
    lightest[root] = std::max(lightest[root], bodies[i].inv_mass);
    heaviest[root] = std::min(heaviest[root], bodies[i].inv_mass);
  }
  for (int i = 0; i < n; ++i) {
    if (bodies[i].IsDynamic() && sets.Root(i) == i && lightest[i] >= ratio * heaviest[i]) return true;
  }
  return false;
}

}  // namespace contactsim
