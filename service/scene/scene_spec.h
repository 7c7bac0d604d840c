// A scene as the engine sees it: world settings and validated-on-build body
// and joint settings, converted from the protobuf Scene
// (service/proto/scene.proto).
#pragma once

#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/physics/body_settings.h"
#include "service/physics/world.h"
#include "service/scene/scene_models.h"

namespace contactsim {

// A joint of a scene: its settings with the bodies still named (resolved to
// ids by BuildWorld).
struct SceneJoint {
  JointSettings settings;
  std::string body_a, body_b;  // body names; empty body_b: the world
};

struct SceneSpec {
  Vec3 gravity = World::DefaultGravity();  // m/s^2
  double dt = World::kDefaultDt;           // s
  Material default_material;
  std::vector<BodySettings> bodies;
  std::vector<std::string> origins;        // "FILE:LINE" of each body, for errors
  std::vector<SceneJoint> joints;
  std::vector<std::string> joint_origins;  // "FILE:LINE: joints[i]" of each joint
  std::vector<SceneModel> models;          // robot models, read with the scene (scene_models.h)
  std::string contact_method;              // empty: keep the current one
  ParamMap method_params;
  int steps = 0;                           // benchmark length; 0: not given
};

// Reads and converts a scene file. Errors name the file, the line and the
// field ("scenes/a.pbtxt:12: bodies[3] \"crate\": radius must be ...").
Status LoadSceneFile(const std::string& path, SceneSpec* scene);
Status ParseSceneText(const std::string& text, const std::string& filename, SceneSpec* scene);

// Builds every body and then every joint (bodies named by a unique name) and
// replaces the world's content only if all are valid; on error the world is
// untouched.
Status BuildWorld(const SceneSpec& scene, World* world);

}  // namespace contactsim
