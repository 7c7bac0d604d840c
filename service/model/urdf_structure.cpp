#include "service/model/urdf_structure.h"

#include <tinyxml.h>

#include "service/model/description_check.h"

namespace contactsim::model {
namespace {

std::string Attribute(const TiXmlElement* e, const char* name) {
  const char* v = e != nullptr ? e->Attribute(name) : nullptr;
  return v != nullptr ? v : "";
}

std::string LineOf(const TiXmlElement* e) { return " (line " + std::to_string(e->Row()) + ")"; }

// The links of <robot>, in order, into the skeleton and the source map.
Status ReadLinks(const TiXmlElement* robot, SourceMap* lines, ModelDescription* skeleton) {
  for (const TiXmlElement* e = robot->FirstChildElement("link"); e != nullptr; e = e->NextSiblingElement("link")) {
    const std::string name = Attribute(e, "name");
    if (name.empty()) return Status::InvalidArgument(lines->File() + "a <link> without a name" + LineOf(e));
    if (lines->link_lines.count(name)) {
      return Status::InvalidArgument(lines->Link(name) + "a second link of this name" + LineOf(e));
    }
    lines->link_lines[name] = e->Row();
    skeleton->links.push_back(Link{name, std::nullopt, {}, {}});
  }
  return Status::Ok();
}

Status ReadJoints(const TiXmlElement* robot, SourceMap* lines, ModelDescription* skeleton) {
  for (const TiXmlElement* e = robot->FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
    ModelJoint j;
    j.name = Attribute(e, "name");
    if (j.name.empty()) return Status::InvalidArgument(lines->File() + "a <joint> without a name" + LineOf(e));
    if (lines->joint_lines.count(j.name)) {
      return Status::InvalidArgument(lines->Joint(j.name) + "a second joint of this name" + LineOf(e));
    }
    lines->joint_lines[j.name] = e->Row();
    const std::string where = lines->Joint(j.name);
    const std::string type = Attribute(e, "type");
    if (!ParseUrdfJointType(type, &j.type)) {
      return Status::InvalidArgument(where + "unknown joint type '" + type +
                                     "' (revolute, continuous, prismatic, fixed, floating, planar are read)");
    }
    j.parent = Attribute(e->FirstChildElement("parent"), "link");
    j.child = Attribute(e->FirstChildElement("child"), "link");
    if (j.parent.empty()) return Status::InvalidArgument(where + "no <parent link=\"...\">");
    if (j.child.empty()) return Status::InvalidArgument(where + "no <child link=\"...\">");
    skeleton->joints.push_back(j);
  }
  return Status::Ok();
}

}  // namespace

bool ParseUrdfJointType(const std::string& word, JointType* type) {
  static const std::pair<const char*, JointType> kTypes[] = {
      {"revolute", JointType::kRevolute}, {"continuous", JointType::kContinuous}, {"prismatic", JointType::kPrismatic},
      {"fixed", JointType::kFixed},       {"floating", JointType::kFloating},     {"planar", JointType::kPlanar}};
  for (const auto& [name, t] : kTypes) {
    if (word == name) {
      *type = t;
      return true;
    }
  }
  return false;
}

Status ReadUrdfStructure(const std::string& text, const ReadLimits& limits, SourceMap* where, UrdfStructure* out) {
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    return Status::InvalidArgument(where->File() + "malformed XML at line " + std::to_string(doc.ErrorRow()) +
                                   ", column " + std::to_string(doc.ErrorCol()) + ": " + doc.ErrorDesc());
  }
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || robot->ValueStr() != "robot") {
    return Status::InvalidArgument(where->File() + "not a URDF: the top element is <" +
                                   (robot != nullptr ? robot->ValueStr() : std::string()) + ">, not <robot>");
  }
  size_t links = 0, joints = 0;
  for (const TiXmlElement* e = robot->FirstChildElement("link"); e; e = e->NextSiblingElement("link")) ++links;
  for (const TiXmlElement* e = robot->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) ++joints;
  Status st = CheckCounts(links, joints, limits, *where);
  if (!st.ok()) return st;
  ModelDescription skeleton;
  st = ReadLinks(robot, where, &skeleton);
  if (st.ok()) st = ReadJoints(robot, where, &skeleton);
  if (st.ok()) st = CheckTree(*where, &skeleton);
  if (!st.ok()) return st;
  out->robot_name = Attribute(robot, "name");
  for (const Link& l : skeleton.links) out->link_order.push_back(l.name);
  for (const ModelJoint& j : skeleton.joints) out->joint_order.push_back(j.name);
  out->root_link = skeleton.root_link;
  return Status::Ok();
}

}  // namespace contactsim::model
