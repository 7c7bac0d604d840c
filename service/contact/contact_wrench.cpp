#include "service/contact/contact_wrench.h"

#include <map>

namespace contactsim {

std::vector<ContactWrench> SumContactWrenches(const World& world, const std::vector<BodyId>& bodies,
                                              const ContactSet& contacts, ContactValueKind kind) {
  std::vector<ContactWrench> out(bodies.size());
  std::multimap<BodyId, int> slots;  // a body may carry several sensors
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) slots.emplace(bodies[i], i);
  const double scale = kind == ContactValueKind::kImpulse ? 1.0 / world.dt : 1.0;
  auto add = [&](BodyId id, double sign, const Contact& c) {
    const auto range = slots.equal_range(id);
    if (range.first == range.second) return;
    const RigidBody* body = world.Find(id);
    if (body == nullptr) return;
    const Vec3 normal = (sign * scale * c.normal_value) * c.normal;
    const Vec3 friction = (sign * scale) * c.tangent_value;
    const Vec3 torque = (c.point - body->x).cross(normal + friction);
    for (auto it = range.first; it != range.second; ++it) {
      ContactWrench& w = out[it->second];
      w.normal_force += normal;
      w.friction_force += friction;
      w.torque += torque;
      ++w.contacts;
    }
  };
  for (const Contact& c : contacts) {
    add(c.id_b, 1.0, c);
    add(c.id_a, -1.0, c);
  }
  return out;
}

}  // namespace contactsim
