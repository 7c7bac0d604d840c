#include "service/model/sdf_reader.h"

#include <sdf/Console.hh>
#include <sdf/ParserConfig.hh>
#include <sdf/Root.hh>
#include <sdf/World.hh>

#include <map>
#include <mutex>

#include "service/model/description_check.h"
#include "service/model/description_meshes.h"
#include "service/model/model_kinematics.h"
#include "service/model/sdf_elements.h"
#include "service/model/sdf_flatten.h"
#include "service/model/source_map.h"

namespace contactsim::model {
namespace {

// Parses the text; <include> URIs resolve with model_paths.h.
Status LoadRoot(const std::string& text, const std::string& base_dir, const ModelPaths& paths, const SourceMap& where,
                sdf::Root* root) {
  static std::once_flag quiet;
  std::call_once(quiet, [] { sdf::Console::Instance()->SetQuiet(true); });  // errors come back as values
  sdf::ParserConfig config;
  config.SetFindCallback([&](const std::string& uri) {
    std::string found;
    return ResolveModelUri(uri, base_dir, paths, &found).ok() ? found : std::string();
  });
  const sdf::Errors errors = root->LoadSdfString(text, config);
  if (!errors.empty()) return Status::InvalidArgument(where.File() + "libsdformat refuses the file: " + FirstError(errors));
  return Status::Ok();
}

Status PickModel(const sdf::Root& root, const SourceMap& where, const sdf::Model** model) {
  if (root.Model() != nullptr) {
    *model = root.Model();
    return Status::Ok();
  }
  if (root.WorldCount() == 0 || root.WorldByIndex(0)->ModelCount() == 0) {
    return Status::InvalidArgument(where.File() + "no <model>, at the top or in a <world>");
  }
  const sdf::World& world = *root.WorldByIndex(0);
  if (root.WorldCount() > 1 || world.ModelCount() > 1) {
    std::string names;
    for (uint64_t i = 0; i < world.ModelCount(); ++i) names += (i ? ", '" : "'") + world.ModelByIndex(i)->Name() + "'";
    return Status::InvalidArgument(where.File() + "the world holds " + std::to_string(world.ModelCount()) +
                                   " models (" + names + "); a file must hold one model");
  }
  *model = world.ModelByIndex(0);
  return Status::Ok();
}

// The flat lists as a description with names only, for the tree check.
ModelDescription Skeleton(const FlatSdfModel& flat) {
  ModelDescription d;
  for (const FlatSdfLink& l : flat.links) d.links.push_back(Link{l.name, std::nullopt, {}, {}});
  for (const FlatSdfJoint& j : flat.joints) {
    ModelJoint mj;
    mj.name = j.name;
    mj.parent = j.parent;
    mj.child = j.child;
    d.joints.push_back(mj);
  }
  return d;
}

// Fills links and joints; a link's frame is its parent joint's frame, the
// root's its own (sdf_reader.h, "Frames").
Status Convert(const FlatSdfModel& flat, const SourceMap& where, ModelDescription* out) {
  std::map<std::string, Pose> frame;
  for (const FlatSdfLink& l : flat.links) frame[l.name] = l.pose;
  for (const FlatSdfJoint& j : flat.joints) frame[j.child] = j.pose;
  for (size_t i = 0; i < flat.links.size(); ++i) {
    Status st = SdfLinkElements(flat.links[i], frame.at(flat.links[i].name), where, &out->links[i]);
    if (!st.ok()) return st;
  }
  for (size_t i = 0; i < flat.joints.size(); ++i) {
    const FlatSdfJoint& j = flat.joints[i];
    ModelJoint& mj = out->joints[i];
    mj.origin = Compose(InversePose(frame.at(j.parent)), frame.at(j.child));
    Status st = SdfJointMotion(*j.joint, where.Joint(j.name), &mj);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

Status CheckWorldJoints(const FlatSdfModel& flat, const SourceMap& where) {
  for (const FlatSdfJoint& j : flat.joints) {
    if (j.parent == "world" || j.child == "world") {
      return Status::InvalidArgument(where.Joint(j.name) +
                                     "a joint to the world is not read; load the model with a fixed base instead");
    }
  }
  return Status::Ok();
}

}  // namespace

Status ReadSdf(const std::string& text, const std::string& source_path, const ModelPaths& paths,
               const ReadLimits& limits, ModelDescription* model) {
  SourceMap where;
  if (Status s = CheckFileSize(text, source_path, limits, &where); !s.ok()) return s;
  sdf::Root root;
  const sdf::Model* top = nullptr;
  Status st = LoadRoot(text, DirectoryOf(where.file), paths, where, &root);
  if (st.ok()) st = PickModel(root, where, &top);
  FlatSdfModel flat;
  if (st.ok()) {
    st = FlattenSdfModel(*top, "", Pose{}, &flat);
    if (!st.ok()) st = st.Prefixed(where.File());
  }
  if (!st.ok()) return st;
  for (const FlatSdfLink& l : flat.links) where.link_lines[l.name] = l.line;
  for (const FlatSdfJoint& j : flat.joints) where.joint_lines[j.name] = j.line;
  ModelDescription out = Skeleton(flat);
  out.name = top->Name();
  out.source = where.file;
  out.self_collide = top->SelfCollide();
  st = CheckCounts(flat.links.size(), flat.joints.size(), limits, where);
  if (st.ok()) st = CheckWorldJoints(flat, where);
  if (st.ok()) st = CheckTree(where, &out);
  if (st.ok()) st = Convert(flat, where, &out);
  if (st.ok()) st = CheckValues(where, &out);
  if (st.ok()) st = ResolveMeshes(DirectoryOf(where.file), paths, limits, where, &out);
  if (!st.ok()) return st;
  *model = std::move(out);
  return Status::Ok();
}

}  // namespace contactsim::model
