#include "service/model/model_file.h"

#include <tinyxml.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "service/model/sdf_reader.h"
#include "service/model/urdf_reader.h"

namespace contactsim::model {

Status DetectModelFormat(const std::string& text, const std::string& source, ModelFormat* format) {
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    return Status::InvalidArgument(source + ": malformed XML at line " + std::to_string(doc.ErrorRow()) + ", column " +
                                   std::to_string(doc.ErrorCol()) + ": " + doc.ErrorDesc());
  }
  const std::string top = doc.RootElement() != nullptr ? doc.RootElement()->ValueStr() : "";
  if (top == "robot") {
    *format = ModelFormat::kUrdf;
  } else if (top == "sdf") {
    *format = ModelFormat::kSdf;
  } else {
    return Status::InvalidArgument(source + ": the top element is <" + top +
                                   ">: neither URDF (<robot>) nor SDF (<sdf>)");
  }
  return Status::Ok();
}

Status ReadModelText(const std::string& text, const std::string& source, const ModelPaths& paths,
                     const ReadLimits& limits, ModelDescription* model) {
  if (text.size() > limits.max_file_bytes) {
    return Status::ResourceExhausted(source + ": " + std::to_string(text.size()) + " bytes, over the limit of " +
                                     std::to_string(limits.max_file_bytes) + " (max_file_bytes)");
  }
  ModelFormat format;
  Status st = DetectModelFormat(text, source, &format);
  if (!st.ok()) return st;
  return format == ModelFormat::kUrdf ? ReadUrdf(text, source, paths, limits, model)
                                      : ReadSdf(text, source, paths, limits, model);
}

Status ReadModelFile(const std::string& name, const ModelPaths& paths, const ReadLimits& limits,
                     ModelDescription* model) {
  std::string path;
  Status st = ResolveModelFile(name, paths, &path);
  if (!st.ok()) return st;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return Status::NotFound(path + ": cannot be read: " + ec.message());
  if (bytes > limits.max_file_bytes) {
    return Status::ResourceExhausted(path + ": " + std::to_string(bytes) + " bytes, over the limit of " +
                                     std::to_string(limits.max_file_bytes) + " (max_file_bytes)");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Status::NotFound(path + ": cannot be read");
  return ReadModelText(text.str(), path, paths, limits, model);
}

}  // namespace contactsim::model
