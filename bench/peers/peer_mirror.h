// What every peer runner shares: reading its settings and checking that the
// scene uses only shapes the peer runner translates, and writing a peer
// body's state into the contactsim World mirror that the metrics read
// (scene_engine.h).
#pragma once

#include <string>

#include "service/contact/param_reader.h"
#include "service/physics/world.h"

namespace contactsim::bench {

// Sets pose and velocity of a mirrored body; v and w in the world frame.
inline void MirrorState(const Vec3& x, const Quat& q, const Vec3& v, const Vec3& w, RigidBody* body) {
  body->x = x;
  body->q = q;
  body->SetVelocity(v, w);
}

// Whether a runner translates static triangle meshes and heightfields
// (Bullet does; ODE and MuJoCo refuse them).
enum SurfaceSupport { kRefusesSurfaces, kTranslatesSurfaces };

// The runners translate spheres, boxes and planes (all the standard scenes
// use), and some static meshes and heightfields; anything else is refused
// with the body named, before any stepping.
inline Status CheckPeerShapes(const World& world, const char* engine, SurfaceSupport surfaces) {
  for (const RigidBody& b : world.bodies()) {
    const ShapeType t = b.shape.type;
    const bool surface = surfaces == kTranslatesSurfaces && b.shape.IsTriangleSurface();
    if (t != ShapeType::kSphere && t != ShapeType::kBox && t != ShapeType::kPlane && !surface) {
      return Status::InvalidArgument(std::string(engine) + " runner: body \"" + b.name + "\" has shape " +
                                     ShapeTypeName(t) + "; only sphere, box" +
                                     (surfaces == kTranslatesSurfaces ? ", plane, mesh and heightfield" : " and plane") +
                                     " are translated");
    }
    if (b.motion == MotionType::kKinematic) {
      return Status::InvalidArgument(std::string(engine) + " runner: body \"" + b.name +
                                     "\" is kinematic; only dynamic and static bodies are translated");
    }
  }
  return Status::Ok();
}

// Whether a runner translates ball joints (Bullet: point-to-point
// constraints); ODE's and MuJoCo's runners translate no joint.
enum JointSupport { kRefusesJoints, kTranslatesBallJoints };

// Refuses, naming the first joint it cannot translate, a scene with joints
// the runner does not build (the joint grids of the scaling benchmark).
inline Status CheckPeerJoints(const World& world, const char* engine, JointSupport joints) {
  for (const Joint& j : world.joints()) {
    if (joints == kTranslatesBallJoints && j.kind == JointKind::kBall) continue;
    return Status::InvalidArgument(std::string(engine) + " runner: joint " + std::to_string(j.id) + " is a " +
                                   JointKindName(j.kind) + " joint (the scene has " +
                                   std::to_string(world.joints().size()) + " joints); " +
                                   (joints == kTranslatesBallJoints ? "only ball joints are translated"
                                                                    : "joints are not translated"));
  }
  return Status::Ok();
}

// A runner's settings before its engine is built: the `iterations`
// parameter of `method` when it takes one (`takes_iterations`; *iterations
// keeps the engine's default otherwise), nothing else, and the scene's
// shapes (meshes and heightfields only where `surfaces` says so) and joints
// (ball joints only where `joints` says so).
inline Status ReadPeerSettings(const char* engine, const char* method, const ParamMap& params, bool takes_iterations,
                               const World& world, int* iterations, SurfaceSupport surfaces = kRefusesSurfaces,
                               JointSupport joints = kRefusesJoints) {
  ParamReader reader(method, params);
  if (takes_iterations) reader.Int("iterations", 1, 100000, iterations);
  Status st = reader.Finish();
  if (st.ok()) st = CheckPeerShapes(world, engine, surfaces);
  return st.ok() ? CheckPeerJoints(world, engine, joints) : st;
}

// A static plane {p : n_W . p <= offset_W} in the world frame.
inline void WorldPlane(const RigidBody& b, Vec3* n_W, double* offset_W) {
  *n_W = b.Rotation() * b.shape.plane_normal;
  *offset_W = b.shape.plane_offset + n_W->dot(b.x);
}

}  // namespace contactsim::bench
