// A model file or text into a description, with the reader its top element
// names: <robot> is URDF (urdf_reader.h), <sdf> is SDF (sdf_reader.h). The
// server's model command, scene files and contactsim-model-info read
// through here.
#pragma once

#include <string>

#include "service/model/model_description.h"
#include "service/model/model_paths.h"
#include "service/model/read_limits.h"
#include "service/physics/status.h"

namespace contactsim::model {

enum class ModelFormat { kUrdf, kSdf };

// The format of a model text by its top element; InvalidArgument (with
// the line of a malformed XML) when it is neither.
Status DetectModelFormat(const std::string& text, const std::string& source, ModelFormat* format);

// Reads `text` (from `source`, a path or "<inline>") with its format's reader.
Status ReadModelText(const std::string& text, const std::string& source, const ModelPaths& paths,
                     const ReadLimits& limits, ModelDescription* model);

// Finds `name` (ResolveModelFile), reads it within limits.max_file_bytes and
// reads the model in it.
Status ReadModelFile(const std::string& name, const ModelPaths& paths, const ReadLimits& limits,
                     ModelDescription* model);

}  // namespace contactsim::model
