#include "service/model/model_source.h"

#include <sys/stat.h>

namespace contactsim::model {
namespace {

bool EndsWith(const std::string& s, const char* tail) {
  const std::string t(tail);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// The first element's name in an XML text, skipping the declaration,
// comments and white space.
std::string RootElement(const std::string& text) {
  size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 2, "<?") == 0 || text.compare(at, 2, "<!") == 0) {
      ++at;
      continue;
    }
    size_t end = text.find_first_of(" \t\r\n/>", at + 1);
    return text.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
  }
  return "";
}

}  // namespace

ModelFormat DetectFormat(const ModelSource& s) {
  if (s.format != ModelFormat::kAuto) return s.format;
  if (!s.path.empty()) {
    if (EndsWith(s.path, ".urdf")) return ModelFormat::kUrdf;
    if (EndsWith(s.path, ".sdf") || EndsWith(s.path, ".world")) return ModelFormat::kSdf;
    return ModelFormat::kAuto;
  }
  const std::string root = RootElement(s.text);
  if (root == "robot") return ModelFormat::kUrdf;
  if (root == "sdf") return ModelFormat::kSdf;
  return ModelFormat::kAuto;
}

Status ReadModelSource(const ModelSource& s, const std::vector<std::string>& search_paths, ModelDescription* d) {
  (void)search_paths;
  (void)d;
  const std::string what = s.path.empty() ? std::string("<inline>") : s.path;
  if (!s.path.empty()) {
    struct stat st;
    if (::stat(s.path.c_str(), &st) != 0) return Status::NotFound(what + ": no such file");
  }
  if (DetectFormat(s) == ModelFormat::kAuto) {
    return Status::InvalidArgument(what + ": neither a URDF (<robot>, .urdf) nor an SDF (<sdf>, .sdf) model");
  }
  return Status::FailedPrecondition(what + ": this build has no URDF or SDF reader");
}

}  // namespace contactsim::model
