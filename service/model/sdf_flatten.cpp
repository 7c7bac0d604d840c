#include "service/model/sdf_flatten.h"

#include <sdf/Element.hh>

#include "service/model/model_kinematics.h"

namespace contactsim::model {
namespace {

int LineOf(const sdf::ElementPtr& e) {
  if (!e) return 0;
  const std::optional<int> line = e->LineNumber();
  return line ? *line : 0;
}

// A scoped link name; the world stays "world".
std::string Scoped(const std::string& prefix, const std::string& name) {
  return name == "world" ? name : prefix + name;
}

Status FlattenJoints(const sdf::Model& model, const std::string& prefix, const Pose& pose, FlatSdfModel* out) {
  for (uint64_t i = 0; i < model.JointCount(); ++i) {
    const sdf::Joint& j = *model.JointByIndex(i);
    FlatSdfJoint flat;
    flat.name = prefix + j.Name();
    flat.joint = &j;
    flat.line = LineOf(j.Element());
    std::string parent, child;
    sdf::Errors errors = j.ResolveParentLink(parent);
    if (errors.empty()) errors = j.ResolveChildLink(child);
    ignition::math::Pose3d p;
    if (errors.empty()) errors = j.SemanticPose().Resolve(p, "__model__");
    if (!errors.empty()) {
      return Status::InvalidArgument("joint '" + flat.name + "' (line " + std::to_string(flat.line) +
                                     "): " + FirstError(errors));
    }
    flat.parent = Scoped(prefix, parent);
    flat.child = Scoped(prefix, child);
    flat.pose = Compose(pose, FromIgnition(p));
    out->joints.push_back(flat);
  }
  return Status::Ok();
}

}  // namespace

Pose FromIgnition(const ignition::math::Pose3d& p) {
  Pose out;
  out.position = Vec3(p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  out.orientation = Quat(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z());
  return out;
}

std::string FirstError(const sdf::Errors& errors) {
  if (errors.empty()) return "";
  const sdf::Error& e = errors.front();
  std::string out = e.Message();
  if (e.LineNumber()) out += " (line " + std::to_string(*e.LineNumber()) + ")";
  if (errors.size() > 1) out += " and " + std::to_string(errors.size() - 1) + " more";
  return out;
}

Status FlattenSdfModel(const sdf::Model& model, const std::string& prefix, const Pose& pose, FlatSdfModel* out) {
  for (uint64_t i = 0; i < model.LinkCount(); ++i) {
    const sdf::Link& l = *model.LinkByIndex(i);
    FlatSdfLink flat;
    flat.name = prefix + l.Name();
    flat.link = &l;
    flat.line = LineOf(l.Element());
    ignition::math::Pose3d p;  // in the model frame, the default resolve-to frame of a link
    const sdf::Errors errors = l.SemanticPose().Resolve(p);
    if (!errors.empty()) {
      return Status::InvalidArgument("link '" + flat.name + "' (line " + std::to_string(flat.line) +
                                     "): " + FirstError(errors));
    }
    flat.pose = Compose(pose, FromIgnition(p));
    out->links.push_back(flat);
  }
  Status st = FlattenJoints(model, prefix, pose, out);
  for (uint64_t i = 0; st.ok() && i < model.ModelCount(); ++i) {
    const sdf::Model& nested = *model.ModelByIndex(i);
    ignition::math::Pose3d p;  // in the parent model frame, a nested model's default
    const sdf::Errors errors = nested.SemanticPose().Resolve(p);
    if (!errors.empty()) {
      return Status::InvalidArgument("model '" + prefix + nested.Name() + "': " + FirstError(errors));
    }
    st = FlattenSdfModel(nested, prefix + nested.Name() + "::", Compose(pose, FromIgnition(p)), out);
  }
  return st;
}

}  // namespace contactsim::model
