// contactsim-model-info: read a URDF or SDF file as the server would and
// print its description as JSON (links with mass, centre-of-mass frame,
// inertia, collision geometry with mesh vertex counts, visuals; joints),
// a quick check of a model file before loading it, e.g.
//
//   contactsim-model-info robot.urdf
//   contactsim-model-info package://my_robot/urdf/arm.urdf --model-path ~/ws/src
//   echo "0.1 0.2 0 0 0 0 0" | contactsim-model-info kuka_iiwa/model.urdf --fk
//
// --fk reads joint coordinates from stdin, one configuration a line (the
// joints' coordinates in the file's joint order; model_kinematics.h), and
// adds "fk": the world pose of every link, the root at the origin.
//
// The search paths are --model-path, then the environment
// (docs/models.md, "How paths resolve"). Exit status: 0 read, 1 refused
// (the message on stderr), CLI11's codes for a bad command line.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "service/model/model_file.h"
#include "service/model/model_kinematics.h"
#include "tools/model_info/model_json.h"

namespace {

using namespace contactsim;

// A name that exists from the working directory is that file; any other
// is looked up as the server would.
std::string FileName(const std::string& name) {
  std::error_code ec;
  if (name.find("://") == std::string::npos && std::filesystem::exists(name, ec)) {
    return std::filesystem::absolute(name).lexically_normal().string();
  }
  return name;
}

Status ReadConfigurations(std::istream& in, const model::ModelDescription& m,
                          std::vector<std::vector<model::Pose>>* poses) {
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::vector<double> q;
    for (double v; s >> v;) q.push_back(v);
    if (q.empty() && line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::vector<model::Pose> p;
    Status st = model::LinkWorldPoses(m, model::Pose{}, q, &p);
    if (!st.ok()) return st;
    poses->push_back(std::move(p));
  }
  return Status::Ok();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Reads a URDF or SDF model file and prints its description as JSON"};
  std::string file;
  std::vector<std::string> model_paths;
  bool fk = false;
  bool no_env = false;
  app.add_option("file", file, "model file: a path, package:// or model:// URI")->required();
  app.add_option("--model-path", model_paths, "directory searched for models and packages (repeatable)");
  app.add_flag("--no-env", no_env, "ignore ROS_PACKAGE_PATH, GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH, SDF_PATH");
  app.add_flag("--fk", fk, "read joint coordinates from stdin and add each link's world pose");
  CLI11_PARSE(app, argc, argv);

  // absolute, so that messages and included files name where they are
  for (std::string& dir : model_paths) dir = std::filesystem::absolute(dir).lexically_normal().string();
  std::vector<std::pair<std::string, std::string>> environment;
  if (!no_env) environment = model::ModelPathEnvironment();
  const model::ModelPaths paths = model::MakeModelPaths(model_paths, {}, environment);
  model::ModelDescription description;
  Status st = model::ReadModelFile(FileName(file), paths, model::ReadLimits{}, &description);
  std::vector<std::vector<model::Pose>> poses;
  if (st.ok() && fk) st = ReadConfigurations(std::cin, description, &poses);
  if (!st.ok()) {
    std::cerr << st.message() << "\n";
    return 1;
  }
  std::string json = tools::DescriptionJson(description);
  if (fk) json = json.substr(0, json.size() - 1) + ",\n \"fk\": " + tools::PosesJson(description, poses) + "}";
  std::cout << json << "\n";
  return 0;
}
