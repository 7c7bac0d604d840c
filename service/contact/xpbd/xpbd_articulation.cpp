#include "service/contact/xpbd/xpbd_articulation.h"

#include "service/contact/xpbd/xpbd_contact.h"

namespace contactsim {

void XpbdArticulation::Prepare(const World& world, const std::vector<SoftBody>& bodies,
                               const std::vector<char>& touching, bool rigid_joints) {
  active_ = rigid_joints && !world.joints().empty();
  if (!active_) return;
  touching_ = touching;
  Build(world, bodies);
  active_ = false;
  for (size_t i = 0; i < touching.size() && !active_; ++i) active_ = mobility_.Jointed(static_cast<int>(i));
}

void XpbdArticulation::Refresh(const World& world, const std::vector<SoftBody>& bodies) {
  if (active_) Build(world, bodies);
}

void XpbdArticulation::Build(const World& world, const std::vector<SoftBody>& bodies) {
  solver_.resize(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    solver_[i].inv_mass = bodies[i].inv_mass;
    solver_[i].inv_inertia = bodies[i].inv_inertia;
  }
  mobility_.Build(world, solver_, touching_);
}

Vec6 XpbdArticulation::Response(int i, const SoftBody& s, const Vec3& lin, const Vec3& ang) const {
  Vec6 g;
  g << lin, ang;
  if (mobility_.Jointed(i)) return mobility_.Own(i) * g;
  Vec6 out;
  out << s.inv_mass * lin, s.inv_inertia * ang;
  return out;
}

Vec6 XpbdArticulation::ResponseOf(int k, int i, const SoftBody& s, const Vec6& w) const {
  if (!mobility_.Jointed(i)) {
    if (k != i) return Vec6::Zero();
    Vec6 out;
    out << s.inv_mass * w.head<3>(), s.inv_inertia * w.tail<3>();
    return out;
  }
  for (const JointMobility::Response* r = mobility_.begin(i); r != mobility_.end(i); ++r) {
    if (r->body == k) return r->z * w;
  }
  return Vec6::Zero();
}

void XpbdArticulation::Displace(World& world, const std::vector<SoftBody>& bodies, int i, const Vec3& force,
                                const Vec3& torque) const {
  auto& all = world.bodies();
  if (!mobility_.Jointed(i)) {
    DisplaceXpbdBody(all[i], bodies[i], bodies[i].inv_mass * force, bodies[i].inv_inertia * torque);
    return;
  }
  Vec6 w;
  w << force, torque;
  for (const JointMobility::Response* r = mobility_.begin(i); r != mobility_.end(i); ++r) {
    const Vec6 d = r->z * w;
    DisplaceXpbdBody(all[r->body], bodies[r->body], d.head<3>(), d.tail<3>());
  }
}

void XpbdArticulation::Kick(std::vector<SoftBody>& bodies, int i, const Vec3& force, const Vec3& torque) const {
  if (!mobility_.Jointed(i)) {
    SoftBody& s = bodies[i];
    if (s.inv_mass == 0.0) return;
    s.v += s.inv_mass * force;
    s.w += s.inv_inertia * torque;
    return;
  }
  Vec6 w;
  w << force, torque;
  for (const JointMobility::Response* r = mobility_.begin(i); r != mobility_.end(i); ++r) {
    SoftBody& s = bodies[r->body];
    if (s.inv_mass == 0.0) continue;
    const Vec6 d = r->z * w;
    s.v += d.head<3>();
    s.w += d.tail<3>();
  }
}

}  // namespace contactsim
