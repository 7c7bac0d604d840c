// Where model files and the meshes they name are looked for, and how the
// URIs of URDF and SDF files become file paths.
//
// The search list is plain data: the server fills it once from its config,
// its --model-path flags and the environment (MakeModelPaths, with
// ModelPathEnvironment the one function that reads the environment), and
// the readers take it as an argument. Order, first match wins:
//   1. --model-path flags, in the order given;
//   2. the server config's model_path entries, in the file's order;
//   3. ROS_PACKAGE_PATH, GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH,
//      SDF_PATH, each split at ':' (kModelPathVariables' order).
// A directory named twice is kept at its first place. Directories are used
// as given: a relative one is relative to the working directory, so a
// caller that wants stable messages and <include>s makes them absolute
// first (contactsim-model-info does). docs/models.md, "How paths resolve",
// gives the rules with examples.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "service/physics/status.h"

namespace contactsim::model {

// The environment variables searched, in their order of precedence: ROS's
// package path first (URDF's package://), then Gazebo's resource paths
// (model://), the new name before the old, then libsdformat's own.
inline constexpr const char* kModelPathVariables[] = {"ROS_PACKAGE_PATH", "GZ_SIM_RESOURCE_PATH",
                                                      "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH"};

struct ModelPaths {
  std::vector<std::string> directories;  // searched in this order
};

// (variable, value) for each of kModelPathVariables that is set, in that
// order: the only place the environment is read.
std::vector<std::pair<std::string, std::string>> ModelPathEnvironment();

// The search list from the flags, the config and the environment, in the
// order the header states; empty entries are dropped and a directory given
// twice keeps its first place.
ModelPaths MakeModelPaths(const std::vector<std::string>& flag_paths, const std::vector<std::string>& config_paths,
                          const std::vector<std::pair<std::string, std::string>>& environment);

// The model file a user names: an absolute path or file:// URI as is; a
// package:// or model:// URI as ResolveModelUri does; a relative path
// against each search directory in order. A Gazebo model folder
// (model://name) stands for the SDF file its model.config names, or its
// model.sdf. NotFound names every place tried.
Status ResolveModelFile(const std::string& name, const ModelPaths& paths, std::string* resolved);

// A file named inside a model file (a mesh, an included model):
//   file:///abs/path                    -> /abs/path
//   package://name/rest                 -> <pkg>/rest, where <pkg> is, in
//       each search directory S in order: S/name if it is a directory, S
//       itself if its package.xml says <name>name</name>, or a directory
//       below S (up to kPackageCrawlDepth levels) whose package.xml does, as
//       ROS and Drake crawl ROS_PACKAGE_PATH; then the model file's own
//       directory and its parents the same way (PyBullet's and Drake's
//       habit of finding the package the model file sits in);
//   model://name/rest                   -> S/name/rest for the first search
//       directory S that has it (Gazebo's resource path), then the model
//       file's directory's parents;
//   an absolute path                    -> as is;
//   a relative path                     -> relative to `base_dir`, the model
//       file's directory (empty for inline text: the search directories).
// The result must exist; NotFound names the URI and the places tried.
Status ResolveModelUri(const std::string& uri, const std::string& base_dir, const ModelPaths& paths,
                       std::string* resolved);

// How deep package:// looks below a search directory for a package.xml.
inline constexpr int kPackageCrawlDepth = 3;

// The directory part of a file path ("" for a bare name or "<inline>").
std::string DirectoryOf(const std::string& path);

}  // namespace contactsim::model
