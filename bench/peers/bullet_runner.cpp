// contactsim-bench-bullet: a benchmark scene in Bullet 3 (Debian
// libbullet-dev, double precision as in PyBullet), with the same flags,
// loop and metrics as contactsim-bench (bench/tools/scene_bench).
//
// Translation: btDiscreteDynamicsWorld with a DBVT broadphase and the
// btSequentialImpulseConstraintSolver at its defaults (10 iterations, split
// impulse, restitution velocity threshold 0.2 m/s); spheres, boxes (with
// Bullet's default 0.04 m margin, inside the box), static planes, and
// static triangle meshes and heightfields (bullet_surfaces.h); ball joints
// as point-to-point constraints (other joint kinds are refused);
// the same masses, principal inertias, poses, velocities, gravity and
// dt (one fixed step per call). Pair materials follow contactsim's rule
// (restitution max, friction sqrt(mu_a mu_b)) through Bullet's combine
// callbacks (Bullet's own rule multiplies them). Deactivation (sleeping) is
// off, as contactsim has none, so every step solves every contact.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "bench/peers/bullet_surfaces.h"
#include "bench/peers/peer_mirror.h"
#include "bench/tools/scene_bench/scene_bench_main.h"
#include "service/contact/contact_row.h"

namespace contactsim::bench {
namespace {

btVector3 Bt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3 FromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

btScalar MaxRestitution(const btCollisionObject* a, const btCollisionObject* b) {
  return std::max(a->getRestitution(), b->getRestitution());
}
btScalar GeometricFriction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::sqrt(a->getFriction() * b->getFriction());
}

class BulletEngine : public SceneEngine {
 public:
  BulletEngine(const World& world, int iterations) : mirror_(world), iterations_(iterations) {
    gCalculateCombinedRestitutionCallback = MaxRestitution;
    gCalculateCombinedFrictionCallback = GeometricFriction;
    gContactAddedCallback = AdjustInternalEdges;
    dynamics_ = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher_, &broadphase_, &solver_, &configuration_);
    dynamics_->setGravity(Bt(world.gravity));
    dynamics_->getSolverInfo().m_numIterations = iterations;
    const auto& bodies = world.bodies();
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i) AddBody(bodies[i], i);
    for (const Joint& j : world.joints()) AddBallJoint(world, j);
  }
  ~BulletEngine() override {
    for (auto& joint : joints_) dynamics_->removeConstraint(joint.get());
    for (auto& body : bodies_) dynamics_->removeRigidBody(body.get());
  }

  void Step() override { dynamics_->stepSimulation(mirror_.dt, 0); }

  const World& Sync() override {
    auto& out = mirror_.bodies();
    for (size_t k = 0; k < bodies_.size(); ++k) {
      if (index_[k] < 0) continue;
      const btTransform& t = bodies_[k]->getCenterOfMassTransform();
      const btQuaternion r = t.getRotation();
      MirrorState(FromBt(t.getOrigin()), Quat(r.w(), r.x(), r.y(), r.z()), FromBt(bodies_[k]->getLinearVelocity()),
                  FromBt(bodies_[k]->getAngularVelocity()), &out[index_[k]]);
    }
    return mirror_;
  }

  ParamMap Params() const override {
    return {{"iterations", std::to_string(iterations_)}, {"broadphase", "dbvt"}, {"precision", "double"}};
  }

 private:
  void AddBody(const RigidBody& b, int index) {
    std::unique_ptr<btCollisionShape> shape;
    btTransform pose;
    pose.setIdentity();
    if (b.shape.type == ShapeType::kPlane) {
      Vec3 n;
      double offset;
      WorldPlane(b, &n, &offset);
      shape = std::make_unique<btStaticPlaneShape>(Bt(n), offset);
    } else if (b.shape.IsTriangleSurface()) {
      return AddSurface(b);
    } else {
      if (b.shape.type == ShapeType::kSphere) {
        shape = std::make_unique<btSphereShape>(b.shape.radius);
      } else {
        shape = std::make_unique<btBoxShape>(Bt(b.shape.half_extents));
      }
      pose.setOrigin(Bt(b.x));
      pose.setRotation(btQuaternion(b.q.x(), b.q.y(), b.q.z(), b.q.w()));
    }
    const bool dynamic = b.IsDynamic();
    // Spheres and boxes have diagonal body-frame inertia about their centre.
    const btVector3 inertia = dynamic ? Bt(b.inertia_body.diagonal()) : btVector3(0, 0, 0);
    btRigidBody::btRigidBodyConstructionInfo info(dynamic ? b.mass : 0.0, nullptr, shape.get(), inertia);
    info.m_startWorldTransform = pose;
    info.m_friction = b.material.friction;
    info.m_restitution = b.material.restitution;
    auto body = std::make_unique<btRigidBody>(info);
    if (dynamic) {
      body->setLinearVelocity(Bt(b.LinearVelocity()));
      body->setAngularVelocity(Bt(b.AngularVelocity()));
      body->setActivationState(DISABLE_DEACTIVATION);
    }
    dynamics_->addRigidBody(body.get());
    index_.push_back(dynamic ? index : -1);
    shapes_.push_back(std::move(shape));
    bodies_.push_back(std::move(body));
  }

  // A ball joint as a point-to-point constraint at the same anchor, given
  // in each body's frame (Bullet's body frame is its centre of mass and
  // principal axes, as contactsim's); the joined bodies do not collide
  // unless the joint says they may (collide_connected).
  void AddBallJoint(const World& world, const Joint& j) {
    const int a = world.IndexOf(j.body_a);
    const RigidBody& body_a = world.bodies()[a];
    const Vec3 anchor = body_a.x + body_a.Rotation() * j.anchor_a;
    std::unique_ptr<btPoint2PointConstraint> joint;
    if (j.body_b == kWorldBody) {
      joint = std::make_unique<btPoint2PointConstraint>(*bodies_[a], Bt(j.anchor_a));
    } else {
      const int b = world.IndexOf(j.body_b);
      const RigidBody& body_b = world.bodies()[b];
      const Vec3 anchor_b = body_b.Rotation().transpose() * (anchor - body_b.x);
      joint = std::make_unique<btPoint2PointConstraint>(*bodies_[a], *bodies_[b], Bt(j.anchor_a), Bt(anchor_b));
    }
    dynamics_->addConstraint(joint.get(), !j.collide_connected);
    joints_.push_back(std::move(joint));
  }

  // A static mesh or heightfield: its shape keeps its data (surfaces_), and
  // its contacts go through the internal-edge correction.
  void AddSurface(const RigidBody& b) {
    std::unique_ptr<BulletSurface> surface =
        b.shape.type == ShapeType::kMesh ? MakeBulletMesh(*b.shape.mesh) : MakeBulletHeightfield(*b.shape.heightfield);
    btTransform pose;
    pose.setOrigin(Bt(b.x + b.Rotation() * FromBt(surface->offset)));
    pose.setRotation(btQuaternion(b.q.x(), b.q.y(), b.q.z(), b.q.w()));
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, surface->shape.get(), btVector3(0, 0, 0));
    info.m_startWorldTransform = pose;
    info.m_friction = b.material.friction;
    info.m_restitution = b.material.restitution;
    auto body = std::make_unique<btRigidBody>(info);
    body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
    dynamics_->addRigidBody(body.get());
    index_.push_back(-1);
    surfaces_.push_back(std::move(surface));
    bodies_.push_back(std::move(body));
  }

  World mirror_;
  int iterations_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> dynamics_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<BulletSurface>> surfaces_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btPoint2PointConstraint>> joints_;
  std::vector<int> index_;  // mirror index of each Bullet body, -1 for static ones
};

Status CreateBulletEngine(const BenchOptions& options, const SceneSpec&, const World& world,
                          std::unique_ptr<SceneEngine>* out) {
  if (options.method != "sequential_impulse") {
    return Status::NotFound("unknown Bullet method \"" + options.method + "\" (known: sequential_impulse)");
  }
  int iterations = 10;  // btContactSolverInfo's default
  const Status st =
      ReadPeerSettings("Bullet", "sequential_impulse", options.params, true, world, &iterations, kTranslatesSurfaces,
                       kTranslatesBallJoints);
  if (!st.ok()) return st;
  *out = std::make_unique<BulletEngine>(world, iterations);
  return Status::Ok();
}

}  // namespace
}  // namespace contactsim::bench

int main(int argc, char** argv) {
  contactsim::bench::RunnerInfo info;
  info.engine = "bullet";
  info.description = "contactsim-bench-bullet: runs a contactsim scene file in Bullet " +
                     std::to_string(btGetVersion()) + " (sequential impulse solver)";
  info.default_method = "sequential_impulse";
  info.methods = {"sequential_impulse"};
  info.factory = contactsim::bench::CreateBulletEngine;
  return contactsim::bench::SceneBenchMain(argc, argv, info);
}
