// Reads config/server.pbtxt-style files (service/proto/config.proto) into
// ServerOptions, the initial scene and the initial contact method.
#pragma once

#include <memory>
#include <string>

#include "service/proto/config.pb.h"
#include "service/scene/scene_spec.h"
#include "service/server/server_options.h"

namespace contactsim {

struct ServerSetup {
  ServerOptions options;
  std::string lcm_url;                  // "" = LCM_DEFAULT_URL or the default
  std::string log_level;
  std::string scene_path;               // "" = empty world
  std::shared_ptr<SceneSpec> scene;     // loaded scene, or null
  std::shared_ptr<ContactMethod> method;
};

// Every error names the file, the line and the field.
Status LoadServerConfig(const std::string& path, proto::ServerConfig* config);
// Validates the config and loads its scene (scene_override wins when set;
// a relative scene path in the config is taken from the config's folder).
Status MakeServerSetup(const proto::ServerConfig& config, const std::string& config_path,
                       const std::string& scene_override, ServerSetup* setup);

}  // namespace contactsim
