// CheckMimics (description_check.h): the mimics of a description, before
// the builder turns them into couplings of the world's joints
// (physics/joint.h, JointMimic).
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "service/model/description_check.h"

namespace contactsim::model {
namespace {

// The coordinate a mimic couples: "hinge" or "prismatic"; empty for the
// types without exactly one coordinate.
std::string CoordinateKind(JointType type) {
  switch (type) {
    case JointType::kRevolute:
    case JointType::kContinuous: return "hinge";
    case JointType::kPrismatic: return "prismatic";
    default: return "";
  }
}

}  // namespace

Status CheckMimics(const SourceMap& where, const ModelDescription& model) {
  std::map<std::string, const ModelJoint*> by_name;
  for (const ModelJoint& j : model.joints) by_name[j.name] = &j;
  for (const ModelJoint& j : model.joints) {
    if (!j.mimic) continue;
    const std::string at = where.Joint(j.name);
    const ModelMimic& m = *j.mimic;
    const auto it = by_name.find(m.joint);
    if (it == by_name.end()) {
      return Status::InvalidArgument(at + "mimic names joint '" + m.joint + "', which the model does not have");
    }
    if (m.joint == j.name) return Status::InvalidArgument(at + "mimic names the joint itself");
    const ModelJoint& master = *it->second;
    const std::string kind = CoordinateKind(j.type);
    if (kind.empty() || kind != CoordinateKind(master.type)) {
      return Status::InvalidArgument(at + "a " + JointTypeName(j.type) + " joint cannot mimic the " + JointTypeName(master.type) +
                                     " joint '" + master.name +
                                     "': a mimic couples two revolute or continuous joints, or two prismatic ones");
    }
    if (!std::isfinite(m.multiplier) || !std::isfinite(m.offset)) {
      return Status::InvalidArgument(at + "mimic multiplier " + std::to_string(m.multiplier) + " and offset " +
                                     std::to_string(m.offset) + " must be finite");
    }
    // follow the masters: a chain of mimics must end at a joint that mimics none
    std::set<std::string> seen = {j.name};
    std::string chain = j.name;
    for (const ModelJoint* at_joint = &master;; at_joint = by_name.at(at_joint->mimic->joint)) {
      chain += " -> " + at_joint->name;
      if (!seen.insert(at_joint->name).second) {
        return Status::InvalidArgument(at + "mimics form a cycle: " + chain);
      }
      if (!at_joint->mimic || !by_name.count(at_joint->mimic->joint)) break;
    }
  }
  return Status::Ok();
}

}  // namespace contactsim::model
