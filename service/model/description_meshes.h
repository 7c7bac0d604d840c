// Turns the mesh file names a reader copied from the file (URIs or paths
// relative to the model file) into resolved paths (model_paths.h), and reads
// the vertices of each collision mesh (mesh_reader.h). A visual mesh is only
// resolved: the viewer loads it. A mesh that cannot be found or read, in a
// collision or a visual, fails the read with the link's name and line.
#pragma once

#include <string>

#include "service/model/model_description.h"
#include "service/model/model_paths.h"
#include "service/model/read_limits.h"
#include "service/model/source_map.h"
#include "service/physics/status.h"

namespace contactsim::model {

// base_dir: the model file's directory ("" for inline text).
Status ResolveMeshes(const std::string& base_dir, const ModelPaths& paths, const ReadLimits& limits,
                     const SourceMap& where, ModelDescription* model);

}  // namespace contactsim::model
