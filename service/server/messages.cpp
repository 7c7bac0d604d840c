#include "service/server/messages.h"

#include "service/server/joint_state_message.h"

namespace contactsim {
state_t MakeStateMessage(const World& world) {
  state_t msg;
  msg.time = world.time;
  msg.step = world.step;
  msg.state_hash = static_cast<int64_t>(HashWorldState(world));
  // energies for plots of a recorded run: masses are not on the wire
  msg.kinetic_energy = KineticEnergy(world);
  msg.potential_energy = PotentialEnergy(world);
  msg.num_bodies = static_cast<int32_t>(world.bodies().size());
  msg.bodies.resize(world.bodies().size());
  for (size_t i = 0; i < world.bodies().size(); ++i) {
    const RigidBody& b = world.bodies()[i];
    body_state_t& s = msg.bodies[i];
    s.id = b.id;
    Copy3(b.x, s.position);
    s.orientation[0] = b.q.w();
    s.orientation[1] = b.q.x();
    s.orientation[2] = b.q.y();
    s.orientation[3] = b.q.z();
    Copy3(b.LinearVelocity(), s.linear_velocity);
    Copy3(b.AngularVelocity(), s.angular_velocity);
  }
  FillStateJoints(world, &msg);
  return msg;
}

contacts_t MakeContactsMessage(const World& world, const ContactSet& contacts, const ContactMethod& method) {
  contacts_t msg;
  msg.time = world.time;
  msg.step = world.step;
  msg.method = method.Name();
  msg.value_kind = method.ValueKind() == ContactValueKind::kImpulse ? contacts_t::IMPULSE : contacts_t::FORCE;
  msg.num_contacts = static_cast<int32_t>(contacts.size());
  msg.contacts.resize(contacts.size());
  for (size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    contact_t& m = msg.contacts[i];
    m.body_a = c.id_a;
    m.body_b = c.id_b;
    Copy3(c.point, m.point);
    Copy3(c.normal, m.normal);
    m.depth = c.depth;
    m.normal_value = c.normal_value;
    Copy3(c.tangent_value, m.tangent_value);
  }
  return msg;
}

reply_t MakeReply(const std::string& client_id, int64_t request_id, const Status& status, const World& world) {
  reply_t r;
  r.client_id = client_id;
  r.request_id = request_id;
  r.code = static_cast<int32_t>(status.code());
  r.message = status.ok() ? (status.message().empty() ? "ok" : status.message()) : status.message();
  r.step = world.step;
  r.time = world.time;
  r.num_ids = 0;
  return r;
}

model_info_t MakeModelInfoMessage(const World& world) {
  model_info_t msg;
  msg.step = world.step;
  msg.num_models = static_cast<int32_t>(world.models.size());
  for (const ModelRecord& m : world.models) {
    model_entry_t e;
    e.model_id = m.id;
    e.name = m.name;
    e.source = m.source;
    e.fixed_base = m.fixed_base;
    e.self_collide = m.self_collide;
    e.num_links = static_cast<int32_t>(m.links.size());
    for (const ModelLinkEntry& l : m.links) {
      e.link_names.push_back(l.name);
      e.link_bodies.push_back(l.body);
      e.link_positions.push_back({l.position.x(), l.position.y(), l.position.z()});
      e.link_orientations.push_back({l.orientation.w(), l.orientation.x(), l.orientation.y(), l.orientation.z()});
    }
    e.num_joints = static_cast<int32_t>(m.joints.size());
    for (const ModelJointEntry& j : m.joints) {
      e.joint_names.push_back(j.name);
      e.joint_types.push_back(j.type);
      e.joint_ids.push_back(j.joint);
      e.joint_damping.push_back(j.damping);
      e.joint_friction.push_back(j.friction);
      e.joint_effort_limits.push_back(j.effort_limit);
      e.joint_velocity_limits.push_back(j.velocity_limit);
    }
    msg.models.push_back(std::move(e));
  }
  return msg;
}

}  // namespace contactsim
