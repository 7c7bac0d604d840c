#include "tools/model_info/model_json.h"

#include <cstdio>
#include <sstream>

#include "tools/json_text.h"

#include "service/model/model_kinematics.h"

namespace contactsim::tools {
namespace {

using model::Geometry;
using model::GeometryType;
using model::JointType;


std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);  // the readers refuse non-finite numbers
  return buf;
}

std::string Array(std::initializer_list<double> values) {
  std::string out = "[";
  for (double v : values) out += (out.size() > 1 ? ", " : "") + Num(v);
  return out + "]";
}

std::string PoseJson(const model::Pose& p) {
  const Quat& q = p.orientation;
  return "{\"position\": " + Array({p.position.x(), p.position.y(), p.position.z()}) +
         ", \"orientation\": " + Array({q.w(), q.x(), q.y(), q.z()}) + "}";
}

const char* TypeName(GeometryType t) {
  switch (t) {
    case GeometryType::kBox: return "box";
    case GeometryType::kSphere: return "sphere";
    case GeometryType::kCylinder: return "cylinder";
    case GeometryType::kCapsule: return "capsule";
    case GeometryType::kMesh: return "mesh";
  }
  return "";
}

std::string GeometryJson(const std::string& name, const model::Pose& origin, const Geometry& g) {
  std::ostringstream o;
  o << "{\"name\": " << JsonQuote(name) << ", \"type\": " << JsonQuote(TypeName(g.type))
    << ", \"origin\": " << PoseJson(origin);
  switch (g.type) {
    case GeometryType::kBox: o << ", \"size\": " << Array({g.box_size.x(), g.box_size.y(), g.box_size.z()}); break;
    case GeometryType::kSphere: o << ", \"radius\": " << Num(g.radius); break;
    case GeometryType::kCylinder:
    case GeometryType::kCapsule: o << ", \"radius\": " << Num(g.radius) << ", \"length\": " << Num(g.length); break;
    case GeometryType::kMesh:
      o << ", \"mesh_path\": " << JsonQuote(g.mesh_path)
        << ", \"mesh_scale\": " << Array({g.mesh_scale.x(), g.mesh_scale.y(), g.mesh_scale.z()})
        << ", \"vertex_count\": " << g.mesh_vertices.size();
      break;
  }
  return o.str();
}

std::string LinkJson(const model::Link& l) {
  std::ostringstream o;
  o << "{\"name\": " << JsonQuote(l.name) << ", \"massless\": " << (l.inertial ? "false" : "true");
  if (l.inertial) {
    const Mat3& I = l.inertial->inertia;
    o << ", \"mass\": " << Num(l.inertial->mass) << ", \"inertial_origin\": " << PoseJson(l.inertial->origin)
      << ", \"inertia\": [" << Array({I(0, 0), I(0, 1), I(0, 2)}) << ", " << Array({I(1, 0), I(1, 1), I(1, 2)}) << ", "
      << Array({I(2, 0), I(2, 1), I(2, 2)}) << "]";
  }
  o << ", \"collisions\": [";
  for (size_t i = 0; i < l.collisions.size(); ++i) {
    o << (i ? ", " : "") << GeometryJson(l.collisions[i].name, l.collisions[i].origin, l.collisions[i].geometry) << "}";
  }
  o << "], \"visuals\": [";
  for (size_t i = 0; i < l.visuals.size(); ++i) {
    const model::VisualElement& v = l.visuals[i];
    o << (i ? ", " : "") << GeometryJson(v.name, v.origin, v.geometry)
      << ", \"rgba\": " << Array({v.rgba(0), v.rgba(1), v.rgba(2), v.rgba(3)}) << "}";
  }
  o << "]}";
  return o.str();
}

std::string JointJson(const model::ModelJoint& j) {
  std::ostringstream o;
  o << "{\"name\": " << JsonQuote(j.name) << ", \"type\": " << JsonQuote(JointTypeName(j.type))
    << ", \"parent\": " << JsonQuote(j.parent)
    << ", \"child\": " << JsonQuote(j.child) << ", \"origin\": " << PoseJson(j.origin)
    << ", \"axis\": " << Array({j.axis.x(), j.axis.y(), j.axis.z()})
    << ", \"coordinates\": " << model::JointCoordinateCount(j.type) << ", \"limits\": ";
  if (j.limits) {
    o << "{\"lower\": " << Num(j.limits->lower) << ", \"upper\": " << Num(j.limits->upper)
      << ", \"effort\": " << Num(j.limits->effort) << ", \"velocity\": " << Num(j.limits->velocity) << "}";
  } else {
    o << "null";
  }
  o << ", \"damping\": " << Num(j.damping) << ", \"friction\": " << Num(j.friction) << "}";
  return o.str();
}

}  // namespace

std::string DescriptionJson(const model::ModelDescription& m) {
  std::ostringstream o;
  o << "{\"name\": " << JsonQuote(m.name) << ", \"source\": " << JsonQuote(m.source)
    << ", \"root_link\": " << JsonQuote(m.root_link)
    << ", \"self_collide\": " << (m.self_collide ? "true" : "false") << ",\n \"links\": [";
  for (size_t i = 0; i < m.links.size(); ++i) o << (i ? ",\n  " : "\n  ") << LinkJson(m.links[i]);
  o << "],\n \"joints\": [";
  for (size_t i = 0; i < m.joints.size(); ++i) o << (i ? ",\n  " : "\n  ") << JointJson(m.joints[i]);
  o << "]}";
  return o.str();
}

std::string PosesJson(const model::ModelDescription& m, const std::vector<std::vector<model::Pose>>& poses) {
  std::ostringstream o;
  o << "[";
  for (size_t c = 0; c < poses.size(); ++c) {
    o << (c ? ",\n  [" : "\n  [");
    for (size_t i = 0; i < poses[c].size(); ++i) {
      const model::Pose& p = poses[c][i];
      const std::string pose = PoseJson(p);
      o << (i ? ", " : "") << "{\"link\": " << JsonQuote(m.links[i].name) << ", " << pose.substr(1);
    }
    o << "]";
  }
  o << "]";
  return o.str();
}

}  // namespace contactsim::tools
