#include "service/model/model_paths.h"

#include <tinyxml.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace contactsim::model {
namespace fs = std::filesystem;

namespace {

bool IsDirectory(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool Exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

// The <name> of the package.xml in `dir`, or "" when there is none.
std::string PackageXmlName(const fs::path& dir) {
  const fs::path xml = dir / "package.xml";
  if (!Exists(xml)) return "";
  TiXmlDocument doc;
  if (!doc.LoadFile(xml.string())) return "";
  const TiXmlElement* root = doc.RootElement();
  const TiXmlElement* name = root != nullptr ? root->FirstChildElement("name") : nullptr;
  return name != nullptr && name->GetText() != nullptr ? name->GetText() : "";
}

// A directory at or below `dir` (at most `depth` levels down) whose
// package.xml names `package`, in directory-name order for determinism. As
// ROS's crawl does, it does not look inside another package.
std::string CrawlForPackage(const fs::path& dir, const std::string& package, int depth) {
  const std::string name = PackageXmlName(dir);
  if (name == package) return dir.string();
  if (depth == 0 || !name.empty()) return "";
  std::vector<fs::path> children;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (IsDirectory(it->path())) children.push_back(it->path());
  }
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) {
    std::string found = CrawlForPackage(child, package, depth - 1);
    if (!found.empty()) return found;
  }
  return "";
}

// The package directory in one search directory, or "".
std::string FindPackageIn(const fs::path& dir, const std::string& package, int depth) {
  if (IsDirectory(dir / package)) return (dir / package).string();
  return CrawlForPackage(dir, package, depth);
}

// Splits "scheme://name/rest" after the scheme into name and rest.
void SplitAuthority(const std::string& after_scheme, std::string* name, std::string* rest) {
  const size_t slash = after_scheme.find('/');
  *name = after_scheme.substr(0, slash);
  *rest = slash == std::string::npos ? "" : after_scheme.substr(slash + 1);
}

bool StartsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

std::string Joined(const std::vector<std::string>& tried) {
  std::string out;
  for (const std::string& t : tried) out += (out.empty() ? "" : ", ") + t;
  return out.empty() ? "no search directories" : out;
}

// The model file's directory and each of its parents, nearest first.
std::vector<fs::path> Ancestors(const std::string& base_dir) {
  std::vector<fs::path> out;
  if (base_dir.empty()) return out;
  for (fs::path p = fs::path(base_dir).lexically_normal(); !p.empty(); p = p.parent_path()) {
    out.push_back(p);
    if (p == p.parent_path()) break;
  }
  return out;
}

Status ResolvePackage(const std::string& uri, const std::string& after, const std::string& base_dir,
                      const ModelPaths& paths, std::string* resolved) {
  std::string package, rest;
  SplitAuthority(after, &package, &rest);
  std::vector<std::string> tried;
  auto try_dir = [&](const fs::path& dir, int depth) {
    const std::string pkg = FindPackageIn(dir, package, depth);
    tried.push_back(dir.string());
    if (pkg.empty() || !Exists(fs::path(pkg) / rest)) return false;
    *resolved = (fs::path(pkg) / rest).string();
    return true;
  };
  for (const std::string& dir : paths.directories) {
    if (try_dir(dir, kPackageCrawlDepth)) return Status::Ok();
  }
  // the package the model file sits in: its directory or a parent of it
  for (const fs::path& dir : Ancestors(base_dir)) {
    if (try_dir(dir, 0)) return Status::Ok();
  }
  return Status::NotFound("cannot resolve '" + uri + "': no package '" + package + "' holding '" + rest +
                          "' in " + Joined(tried));
}

Status ResolveModelScheme(const std::string& uri, const std::string& after, const std::string& base_dir,
                          const ModelPaths& paths, std::string* resolved) {
  std::vector<std::string> tried;
  std::vector<fs::path> dirs(paths.directories.begin(), paths.directories.end());
  // a model:// inside a model file names a sibling model directory
  const std::vector<fs::path> up = Ancestors(base_dir);
  if (up.size() > 1) dirs.push_back(up[1]);
  for (const fs::path& dir : dirs) {
    tried.push_back(dir.string());
    if (Exists(dir / after)) {
      *resolved = (dir / after).string();
      return Status::Ok();
    }
  }
  return Status::NotFound("cannot resolve '" + uri + "': not in " + Joined(tried));
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ModelPathEnvironment() {
  std::vector<std::pair<std::string, std::string>> env;
  for (const char* name : kModelPathVariables) {
    if (const char* value = std::getenv(name)) env.emplace_back(name, value);
  }
  return env;
}

ModelPaths MakeModelPaths(const std::vector<std::string>& flag_paths, const std::vector<std::string>& config_paths,
                          const std::vector<std::pair<std::string, std::string>>& environment) {
  ModelPaths out;
  auto add = [&out](const std::string& dir) {
    if (dir.empty()) return;
    for (const std::string& d : out.directories) {
      if (d == dir) return;
    }
    out.directories.push_back(dir);
  };
  for (const std::string& d : flag_paths) add(d);
  for (const std::string& d : config_paths) add(d);
  // each variable in kModelPathVariables' order, whatever order they came in
  for (const char* name : kModelPathVariables) {
    for (const auto& [var, value] : environment) {
      if (var != name) continue;
      size_t start = 0;
      while (start <= value.size()) {
        const size_t colon = std::min(value.find(':', start), value.size());
        add(value.substr(start, colon - start));
        start = colon + 1;
      }
    }
  }
  return out;
}

std::string DirectoryOf(const std::string& path) {
  if (path.empty() || path == "<inline>") return "";
  return fs::path(path).parent_path().string();
}

Status ResolveModelUri(const std::string& uri, const std::string& base_dir, const ModelPaths& paths,
                       std::string* resolved) {
  if (uri.empty()) return Status::InvalidArgument("an empty file name");
  if (StartsWith(uri, "package://")) return ResolvePackage(uri, uri.substr(10), base_dir, paths, resolved);
  if (StartsWith(uri, "model://")) return ResolveModelScheme(uri, uri.substr(8), base_dir, paths, resolved);
  if (uri.find("://") != std::string::npos && !StartsWith(uri, "file://")) {
    return Status::InvalidArgument("unsupported URI scheme in '" + uri + "' (file://, package://, model:// are read)");
  }
  const std::string path = StartsWith(uri, "file://") ? uri.substr(7) : uri;
  std::vector<fs::path> candidates;
  if (fs::path(path).is_absolute()) {
    candidates.push_back(path);
  } else if (!base_dir.empty()) {
    candidates.push_back(fs::path(base_dir) / path);
  } else {
    for (const std::string& dir : paths.directories) candidates.push_back(fs::path(dir) / path);
  }
  std::vector<std::string> tried;
  for (const fs::path& c : candidates) {
    tried.push_back(c.string());
    if (Exists(c)) {
      *resolved = c.lexically_normal().string();
      return Status::Ok();
    }
  }
  if (tried.empty()) return Status::NotFound("cannot find '" + uri + "': a relative name and no search directories");
  return Status::NotFound("cannot find '" + uri + "' (tried " + Joined(tried) + ")");
}

Status ResolveModelFile(const std::string& name, const ModelPaths& paths, std::string* resolved) {
  // a relative name is looked up in the search directories, not the cwd
  std::string path;
  Status st = ResolveModelUri(name, "", paths, &path);
  if (!st.ok() || !IsDirectory(path)) {
    *resolved = path;
    return st;
  }
  // a Gazebo model folder: the SDF file its model.config names
  TiXmlDocument config;
  const TiXmlElement* sdf = nullptr;
  if (config.LoadFile((fs::path(path) / "model.config").string()) && config.RootElement() != nullptr) {
    sdf = config.RootElement()->FirstChildElement("sdf");
  }
  const fs::path file = fs::path(path) / (sdf != nullptr && sdf->GetText() != nullptr ? sdf->GetText() : "model.sdf");
  if (!Exists(file)) return Status::NotFound("'" + name + "' is a folder without model.config or model.sdf");
  *resolved = file.string();
  return Status::Ok();
}

}  // namespace contactsim::model
