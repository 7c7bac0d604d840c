// contactsim-bench-box3d: a benchmark scene in Box3D (built from a Box3D
// checkout given at configure time: bench/peers/CMakeLists.txt), with the
// same flags, loop and metrics as contactsim-bench (bench/tools/scene_bench).
//
// Translation: a b3World at Box3D's defaults (single precision, its SIMD
// path, 4 sub-steps a step, contact hertz 30, damping ratio 10, push speed
// 3 m/s, restitution threshold 1 m/s, continuous collision on, speculative
// contacts), but for sleeping, which is off for the world and every body, so
// that every step solves every contact. Spheres as sphere shapes, boxes as
// box hulls (b3MakeBoxHull); Box3D has no plane, so a static plane is a
// static box whose top face is the plane (2 kGroundHalfHeight thick, wide
// enough to hold every body of the scene). Dynamic bodies get contactsim's
// mass and principal inertia explicitly (b3Body_SetMassData; the shapes add
// no mass), and the same poses, velocities, gravity and dt (one b3World_Step
// a call). Materials: per shape, the body's friction and restitution; Box3D's
// default mixing is contactsim's pair rule (friction sqrt(mu_a mu_b),
// restitution max: b3WorldDef's frictionCallback and restitutionCallback
// left null), so no callback is installed. --threads N > 1 gives the world
// N workers through its task callbacks (box3d_task_pool.h); --threads 1
// steps serially on the caller, with no task system at all.
#include <box3d/box3d.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench/peers/box3d_task_pool.h"
#include "bench/peers/peer_mirror.h"
#include "bench/tools/scene_bench/scene_bench_main.h"
#include "service/contact/param_reader.h"

#ifndef CONTACTSIM_BOX3D_COMMIT
#define CONTACTSIM_BOX3D_COMMIT "unknown"
#endif

namespace contactsim::bench {
namespace {

constexpr float kGroundHalfHeight = 1.0f;  // m, as the ground boxes of Box3D's samples
constexpr double kGroundMargin = 10.0;   // m of ground beyond the farthest body

// What --param may change; Box3D's defaults otherwise.
struct Box3dSettings {
  int substeps = 4;             // b3World_Step's sub-steps: Box3D's samples and benchmark use 4
  double contact_hertz = 30.0;  // Hz, b3DefaultWorldDef's contactHertz (static contacts get twice it)
};

b3Vec3 B3(const Vec3& v) { return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())}; }
Vec3 FromB3(const b3Vec3& v) { return Vec3(v.x, v.y, v.z); }
b3Quat B3(const Quat& q) {
  return {{static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())}, static_cast<float>(q.w())};
}

std::string VersionText() {
  const b3Version v = b3GetVersion();
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.revision) + " (" +
         CONTACTSIM_BOX3D_COMMIT + ")";
}

// Half the side of the square ground box under a plane: the plane's point
// nearest the origin to the farthest body, plus a margin.
double GroundHalfWidth(const World& world, const Vec3& plane_point) {
  double reach = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (!b.shape.IsPlane()) reach = std::max(reach, (b.x - plane_point).norm());
  }
  return reach + kGroundMargin;
}

class Box3dEngine : public SceneEngine {
 public:
  Box3dEngine(const World& world, const Box3dSettings& settings, int threads)
      : mirror_(world), settings_(settings), threads_(threads) {
    b3WorldDef def = b3DefaultWorldDef();
    def.gravity = B3(world.gravity);
    def.contactHertz = static_cast<float>(settings.contact_hertz);
    def.enableSleep = false;
    if (threads > 1) {
      pool_ = std::make_unique<Box3dTaskPool>(threads);
      def.workerCount = static_cast<uint32_t>(threads);
      def.enqueueTask = &Box3dTaskPool::Enqueue;
      def.finishTask = &Box3dTaskPool::Finish;
      def.userTaskContext = pool_.get();
    }
    world_ = b3CreateWorld(&def);
    const auto& bodies = world.bodies();
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i) AddBody(world, bodies[i], i);
  }
  ~Box3dEngine() override { b3DestroyWorld(world_); }  // before the pool its tasks run on

  void Step() override { b3World_Step(world_, static_cast<float>(mirror_.dt), settings_.substeps); }

  const World& Sync() override {
    auto& out = mirror_.bodies();
    for (size_t k = 0; k < bodies_.size(); ++k) {
      const b3Quat r = b3Body_GetRotation(bodies_[k]);
      const Quat q = Quat(r.s, r.v.x, r.v.y, r.v.z).normalized();
      MirrorState(FromB3(b3Body_GetPosition(bodies_[k])), q, FromB3(b3Body_GetLinearVelocity(bodies_[k])),
                  FromB3(b3Body_GetAngularVelocity(bodies_[k])), &out[index_[k]]);
    }
    return mirror_;
  }

  ParamMap Params() const override {
    return {{"substeps", std::to_string(settings_.substeps)},
            {"contact_hertz", std::to_string(settings_.contact_hertz)},
            {"damping_ratio", std::to_string(b3DefaultWorldDef().contactDampingRatio)},
            {"precision", "float"},
            {"simd", "sse2"},
            {"threads", std::to_string(threads_)},
            {"version", VersionText()}};
  }

 private:
  // A scene body as a Box3D body with one shape; a plane becomes a static
  // box under it, the dynamic bodies are kept for Sync.
  void AddBody(const World& world, const RigidBody& b, int index) {
    b3BodyDef body_def = b3DefaultBodyDef();
    body_def.enableSleep = false;
    b3ShapeDef shape_def = b3DefaultShapeDef();
    shape_def.baseMaterial.friction = static_cast<float>(b.material.friction);
    shape_def.baseMaterial.restitution = static_cast<float>(b.material.restitution);
    if (b.shape.IsPlane()) {
      Vec3 n;
      double offset;
      WorldPlane(b, &n, &offset);
      const Vec3 top = offset * n;
      const float half_width = static_cast<float>(GroundHalfWidth(world, top));
      body_def.position = B3(top - kGroundHalfHeight * n);
      body_def.rotation = B3(Quat::FromTwoVectors(Vec3::UnitZ(), n));
      const b3BoxHull hull = b3MakeBoxHull(half_width, half_width, kGroundHalfHeight);
      b3CreateHullShape(b3CreateBody(world_, &body_def), &shape_def, &hull.base);
      return;
    }
    const bool dynamic = b.IsDynamic();
    body_def.type = dynamic ? b3_dynamicBody : b3_staticBody;
    body_def.position = B3(b.x);
    body_def.rotation = B3(b.q);
    if (dynamic) {
      body_def.linearVelocity = B3(b.LinearVelocity());
      body_def.angularVelocity = B3(b.AngularVelocity());
    }
    const b3BodyId body = b3CreateBody(world_, &body_def);
    shape_def.updateBodyMass = false;  // the mass comes from the scene, below
    if (b.shape.type == ShapeType::kSphere) {
      const b3Sphere sphere = {{0.0f, 0.0f, 0.0f}, static_cast<float>(b.shape.radius)};
      b3CreateSphereShape(body, &shape_def, &sphere);
    } else {
      const b3Vec3 h = B3(b.shape.half_extents);
      const b3BoxHull hull = b3MakeBoxHull(h.x, h.y, h.z);
      b3CreateHullShape(body, &shape_def, &hull.base);
    }
    if (!dynamic) return;
    // spheres and boxes have diagonal body-frame inertia about their centre
    const Vec3 inertia = b.inertia_body.diagonal();
    b3MassData mass = {};
    mass.mass = static_cast<float>(b.mass);
    mass.inertia.cx.x = static_cast<float>(inertia.x());
    mass.inertia.cy.y = static_cast<float>(inertia.y());
    mass.inertia.cz.z = static_cast<float>(inertia.z());
    b3Body_SetMassData(body, mass);
    bodies_.push_back(body);
    index_.push_back(index);
  }

  World mirror_;
  Box3dSettings settings_;
  int threads_;
  std::unique_ptr<Box3dTaskPool> pool_;  // null on one thread
  b3WorldId world_;
  std::vector<b3BodyId> bodies_;  // the dynamic bodies
  std::vector<int> index_;        // mirror index of each of bodies_
};

Status CreateBox3dEngine(const BenchOptions& options, const SceneSpec&, const World& world,
                         std::unique_ptr<SceneEngine>* out) {
  if (options.method != "soft_step") {
    return Status::NotFound("unknown Box3D method \"" + options.method + "\" (known: soft_step)");
  }
  if (options.threads > B3_MAX_WORKERS) {
    return Status::InvalidArgument("Box3D runner: --threads " + std::to_string(options.threads) +
                                   " is above Box3D's B3_MAX_WORKERS (" + std::to_string(B3_MAX_WORKERS) + ")");
  }
  Box3dSettings settings;
  ParamReader reader(options.method.c_str(), options.params);
  reader.Int("substeps", 1, 1000, &settings.substeps);
  reader.Double("contact_hertz", 0.1, 1e4, &settings.contact_hertz);
  Status st = reader.Finish();
  if (st.ok()) st = CheckPeerShapes(world, "Box3D", kRefusesSurfaces);
  if (st.ok()) st = CheckPeerJoints(world, "Box3D", kRefusesJoints);
  if (!st.ok()) return st;
  *out = std::make_unique<Box3dEngine>(world, settings, options.threads);
  return Status::Ok();
}

}  // namespace
}  // namespace contactsim::bench

int main(int argc, char** argv) {
  contactsim::bench::RunnerInfo info;
  info.engine = "box3d";
  info.description =
      "contactsim-bench-box3d: runs a contactsim scene file in Box3D " + contactsim::bench::VersionText() +
      " (soft step)";
  info.default_method = "soft_step";
  info.methods = {"soft_step"};
  info.threaded = true;
  info.factory = contactsim::bench::CreateBox3dEngine;
  return contactsim::bench::SceneBenchMain(argc, argv, info);
}
