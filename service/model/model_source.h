// Where a model comes from: a file path or the file's text, and its format
// (URDF or SDF, given or detected). ReadModelSource hands it to the reader
// of its format (urdf_reader.h, sdf_reader.h), which resolves meshes and
// package:// and model:// URIs against the search paths (docs/models.md,
// "Paths").
#pragma once

#include <string>
#include <vector>

#include "service/model/model_description.h"
#include "service/physics/status.h"

namespace contactsim::model {

enum class ModelFormat { kAuto, kUrdf, kSdf };

struct ModelSource {
  std::string path;                 // a file; empty when text is given
  std::string text;                 // the file's text inline
  ModelFormat format = ModelFormat::kAuto;
};

// The format a source names or shows: the path's extension (.urdf, .sdf,
// .world), else the root element of the text (<robot>, <sdf>); kAuto when
// neither tells.
ModelFormat DetectFormat(const ModelSource& source);

// Reads the source into a description; the error names the file (or
// "<inline>"), the element and where the parser says it is.
Status ReadModelSource(const ModelSource& source, const std::vector<std::string>& search_paths,
                       ModelDescription* description);

}  // namespace contactsim::model
