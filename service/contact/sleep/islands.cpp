#include "service/contact/sleep/islands.h"

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

bool Joins(const RigidBody& b) { return b.IsDynamic() && !b.asleep(); }

}  // namespace

std::vector<int> FindIslands(const World& world, const ContactSet& contacts, const std::vector<BodyPair>& near) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  auto join = [&](int a, int b) {
    if (a >= 0 && b >= 0 && Joins(bodies[a]) && Joins(bodies[b])) sets.Join(a, b);
  };
  for (const Contact& c : contacts) join(c.a, c.b);
  for (const Joint& j : world.joints()) {
    if (j.body_b != kWorldBody) join(world.IndexOf(j.body_a), world.IndexOf(j.body_b));
    // a mimic's row joins its bodies with its master's: they sleep together
    if (const Joint* m = j.mimic.master != 0 ? world.FindJoint(j.mimic.master) : nullptr) {
      for (const BodyId f : {j.body_a, j.body_b}) {
        for (const BodyId g : {m->body_a, m->body_b}) {
          if (f != kWorldBody && g != kWorldBody) join(world.IndexOf(f), world.IndexOf(g));
        }
      }
    }
  }
  for (const BodyPair& p : near) join(p.first, p.second);
  // the union by smaller index makes each root its island's first body
  std::vector<int> root(n, -1);
  for (int i = 0; i < n; ++i) {
    if (Joins(bodies[i])) root[i] = sets.Root(i);
  }
  return root;
}

}  // namespace contactsim
