// contactsim-bench-ode: a benchmark scene in ODE 0.16 (Debian libode-dev,
// double precision), with the same flags, loop and metrics as
// contactsim-bench (bench/tools/scene_bench).
//
// Methods: "quickstep" (dWorldQuickStep, projected SOR, 20 iterations) and
// "dantzig" (dWorldStep: Dantzig's pivoting LCP over each island, exact
// but O(rows^3)). Translation: a hash space; spheres, boxes and planes
// (static ones as body-less geoms); the same masses, principal inertias,
// poses, velocities, gravity and dt. Up to 4 contacts per pair (dCollide),
// each with a friction pyramid scaled by the normal force
// (dContactApprox1, mu = sqrt(mu_a mu_b)) and, when the pair's restitution
// max(e_a, e_b) is positive, dContactBounce with bounce_vel 0.2 m/s (as
// Bullet's threshold). World ERP and CFM stay at ODE's defaults (0.2 and
// 1e-10 in double precision); auto-disable stays off, as in ODE by default.
#include <ode/ode.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "bench/peers/peer_mirror.h"
#include "bench/tools/scene_bench/scene_bench_main.h"
#include "service/contact/contact_row.h"

namespace contactsim::bench {
namespace {

constexpr int kMaxContactsPerPair = 4;
constexpr double kBounceVelocity = 0.2;  // m/s, below it no bounce

class OdeEngine : public SceneEngine {
 public:
  OdeEngine(const World& world, bool quickstep, int iterations)
      : mirror_(world), quickstep_(quickstep), iterations_(iterations) {
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    contact_group_ = dJointGroupCreate(0);
    dWorldSetGravity(world_, world.gravity.x(), world.gravity.y(), world.gravity.z());
    dWorldSetQuickStepNumIterations(world_, iterations);
    const auto& bodies = world.bodies();
    materials_.reserve(bodies.size());
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i) AddBody(bodies[i], i);
  }
  ~OdeEngine() override {
    dJointGroupDestroy(contact_group_);
    dSpaceDestroy(space_);  // destroys its geoms
    dWorldDestroy(world_);  // and its bodies
  }

  void Step() override {
    dSpaceCollide(space_, this, &OdeEngine::NearCallback);
    if (quickstep_) {
      dWorldQuickStep(world_, mirror_.dt);
    } else {
      dWorldStep(world_, mirror_.dt);
    }
    dJointGroupEmpty(contact_group_);
  }

  const World& Sync() override {
    auto& out = mirror_.bodies();
    for (const auto& [body, index] : dynamic_) {
      const dReal* x = dBodyGetPosition(body);
      const dReal* q = dBodyGetQuaternion(body);
      const dReal* v = dBodyGetLinearVel(body);
      const dReal* w = dBodyGetAngularVel(body);
      MirrorState(Vec3(x[0], x[1], x[2]), Quat(q[0], q[1], q[2], q[3]), Vec3(v[0], v[1], v[2]),
                  Vec3(w[0], w[1], w[2]), &out[index]);
    }
    return mirror_;
  }

  ParamMap Params() const override {
    char erp[32], cfm[32];
    std::snprintf(erp, sizeof erp, "%g", dWorldGetERP(world_));
    std::snprintf(cfm, sizeof cfm, "%g", dWorldGetCFM(world_));
    ParamMap p = {{"space", "hash"}, {"erp", erp}, {"cfm", cfm}};
    if (quickstep_) p["iterations"] = std::to_string(iterations_);
    return p;
  }

 private:
  void AddBody(const RigidBody& b, int index) {
    materials_.push_back(b.material);
    dGeomID geom;
    if (b.shape.type == ShapeType::kPlane) {
      Vec3 n;
      double offset;
      WorldPlane(b, &n, &offset);
      geom = dCreatePlane(space_, n.x(), n.y(), n.z(), offset);
    } else {
      if (b.shape.type == ShapeType::kSphere) {
        geom = dCreateSphere(space_, b.shape.radius);
      } else {
        const Vec3 size = 2.0 * b.shape.half_extents;
        geom = dCreateBox(space_, size.x(), size.y(), size.z());
      }
      const dQuaternion q = {b.q.w(), b.q.x(), b.q.y(), b.q.z()};
      if (b.IsDynamic()) {
        dBodyID body = dBodyCreate(world_);
        dMass mass;
        const Mat3& I = b.inertia_body;
        dMassSetParameters(&mass, b.mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
        dBodySetMass(body, &mass);
        dGeomSetBody(geom, body);
        dBodySetPosition(body, b.x.x(), b.x.y(), b.x.z());
        dBodySetQuaternion(body, q);
        const Vec3 v = b.LinearVelocity(), w = b.AngularVelocity();
        dBodySetLinearVel(body, v.x(), v.y(), v.z());
        dBodySetAngularVel(body, w.x(), w.y(), w.z());
        dynamic_.emplace_back(body, index);
      } else {
        dGeomSetPosition(geom, b.x.x(), b.x.y(), b.x.z());
        dGeomSetQuaternion(geom, q);
      }
    }
    dGeomSetData(geom, &materials_.back());
  }

  static void NearCallback(void* data, dGeomID a, dGeomID b) {
    auto* self = static_cast<OdeEngine*>(data);
    dBodyID body_a = dGeomGetBody(a), body_b = dGeomGetBody(b);
    if (!body_a && !body_b) return;  // two static geoms
    dContactGeom geoms[kMaxContactsPerPair];
    const int n = dCollide(a, b, kMaxContactsPerPair, geoms, sizeof(dContactGeom));
    if (n == 0) return;
    const Material& ma = *static_cast<const Material*>(dGeomGetData(a));
    const Material& mb = *static_cast<const Material*>(dGeomGetData(b));
    const double restitution = CombineRestitution(ma, mb);
    for (int i = 0; i < n; ++i) {
      dContact contact{};
      contact.geom = geoms[i];
      contact.surface.mode = dContactApprox1;
      contact.surface.mu = CombineFriction(ma, mb);
      if (restitution > 0.0) {
        contact.surface.mode |= dContactBounce;
        contact.surface.bounce = restitution;
        contact.surface.bounce_vel = kBounceVelocity;
      }
      dJointID joint = dJointCreateContact(self->world_, self->contact_group_, &contact);
      dJointAttach(joint, body_a, body_b);
    }
  }

  World mirror_;
  bool quickstep_;
  int iterations_;
  dWorldID world_;
  dSpaceID space_;
  dJointGroupID contact_group_;
  std::vector<Material> materials_;  // per geom, in dGeomGetData (reserved: no reallocation)
  std::vector<std::pair<dBodyID, int>> dynamic_;  // ODE body, mirror index
};

// dInitODE2 once per process; the engines of the repeats share it.
struct OdeLibrary {
  OdeLibrary() { dInitODE2(0); }
  ~OdeLibrary() { dCloseODE(); }
};

Status CreateOdeEngine(const BenchOptions& options, const SceneSpec&, const World& world,
                       std::unique_ptr<SceneEngine>* out) {
  static OdeLibrary library;
  const bool quickstep = options.method == "quickstep";
  if (!quickstep && options.method != "dantzig") {
    return Status::NotFound("unknown ODE method \"" + options.method + "\" (known: quickstep, dantzig)");
  }
  int iterations = 20;
  const Status st = ReadPeerSettings("ODE", options.method.c_str(), options.params, quickstep, world, &iterations);
  if (!st.ok()) return st;
  *out = std::make_unique<OdeEngine>(world, quickstep, iterations);
  return Status::Ok();
}

}  // namespace
}  // namespace contactsim::bench

int main(int argc, char** argv) {
  contactsim::bench::RunnerInfo info;
  info.engine = "ode";
  info.description = "contactsim-bench-ode: runs a contactsim scene file in ODE (QuickStep or Dantzig LCP step)";
  info.default_method = "quickstep";
  info.methods = {"quickstep", "dantzig"};
  info.factory = contactsim::bench::CreateOdeEngine;
  return contactsim::bench::SceneBenchMain(argc, argv, info);
}
