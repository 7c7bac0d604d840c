#include "service/model/model_check.h"

#include <Eigen/Eigenvalues>
#include <map>

#include "service/physics/validation.h"

namespace contactsim::model {
namespace {

// The largest length and mass we accept, as for plain bodies: beyond them
// double precision and the broadphase stop being meaningful.
constexpr double kMaxLength = 1e6;  // m
constexpr double kMaxMass = 1e9;    // kg

Status Refuse(const std::string& where, const std::string& what) {
  return Status::InvalidArgument(where + ": " + what);
}

Status CheckPose(const std::string& where, const Pose& p) {
  if (!p.position.allFinite() || p.position.cwiseAbs().maxCoeff() > kMaxLength) {
    return Refuse(where, "origin position " + FormatValue(p.position) + " is not finite or beyond 1e6 m");
  }
  if (!p.orientation.coeffs().allFinite() || std::abs(p.orientation.norm() - 1.0) > 1e-6) {
    return Refuse(where, "origin orientation is not a unit quaternion");
  }
  return Status::Ok();
}

Status CheckGeometry(const std::string& where, const Geometry& g) {
  auto positive = [&](const char* field, double v) {
    return v > 0.0 && v <= kMaxLength ? Status::Ok()
                                      : Refuse(where, std::string(field) + " must be in (0, 1e6] m, got " + FormatValue(v));
  };
  switch (g.type) {
    case GeometryType::kBox:
      for (int i = 0; i < 3; ++i) {
        if (Status st = positive("box size", g.box_size[i]); !st.ok()) return st;
      }
      return Status::Ok();
    case GeometryType::kSphere: return positive("radius", g.radius);
    case GeometryType::kCylinder:
    case GeometryType::kCapsule:
      if (Status st = positive("radius", g.radius); !st.ok()) return st;
      return positive("length", g.length);
    case GeometryType::kMesh:
      if (g.mesh_vertices.size() < 4) {
        return Refuse(where, "mesh " + g.mesh_path + " has " + std::to_string(g.mesh_vertices.size()) +
                                 " vertices; its convex hull needs at least 4");
      }
      for (const Vec3& v : g.mesh_vertices) {
        if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxLength) {
          return Refuse(where, "mesh " + g.mesh_path + " has a vertex " + FormatValue(v) + " that is not finite");
        }
      }
      return Status::Ok();
  }
  return Refuse(where, "unknown geometry type");
}

Status CheckLink(const std::string& where, const Link& link) {
  if (link.inertial) {
    const Inertial& in = *link.inertial;
    if (!(in.mass > 0.0 && in.mass <= kMaxMass)) {
      return Refuse(where, "mass must be in (0, 1e9] kg, got " + FormatValue(in.mass));
    }
    if (Status st = CheckPose(where + " inertial", in.origin); !st.ok()) return st;
    if (Status st = CheckInertia(where, in.inertia); !st.ok()) return st;
  }
  for (size_t i = 0; i < link.collisions.size(); ++i) {
    const std::string w = where + " collision " + std::to_string(i);
    if (Status st = CheckPose(w, link.collisions[i].origin); !st.ok()) return st;
    if (Status st = CheckGeometry(w, link.collisions[i].geometry); !st.ok()) return st;
  }
  return Status::Ok();
}

Status CheckJoint(const std::string& where, const ModelJoint& j) {
  if (Status st = CheckPose(where, j.origin); !st.ok()) return st;
  const bool moves = j.type == JointType::kRevolute || j.type == JointType::kContinuous ||
                     j.type == JointType::kPrismatic;
  if (moves && (!j.axis.allFinite() || j.axis.norm() < 1e-9)) {
    return Refuse(where, "axis " + FormatValue(j.axis) + " is not a nonzero finite vector");
  }
  if (j.limits && (j.type == JointType::kRevolute || j.type == JointType::kPrismatic)) {
    const JointLimits& l = *j.limits;
    if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || l.lower > l.upper) {
      return Refuse(where, "limits lower " + FormatValue(l.lower) + " and upper " + FormatValue(l.upper) +
                               " must be finite with lower <= upper");
    }
  }
  if (!(j.damping >= 0.0 && std::isfinite(j.damping)) || !(j.friction >= 0.0 && std::isfinite(j.friction))) {
    return Refuse(where, "damping " + FormatValue(j.damping) + " and friction " + FormatValue(j.friction) +
                             " must be finite and >= 0");
  }
  return Status::Ok();
}

}  // namespace

std::string ModelWhere(const ModelDescription& d) { return "model \"" + d.name + "\" (" + d.source + ")"; }

Status CheckInertia(const std::string& where, const Mat3& I) {
  if (!I.allFinite() || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + I.cwiseAbs().maxCoeff())) {
    return Refuse(where, "inertia is not a finite symmetric matrix");
  }
  const Vec3 m = Eigen::SelfAdjointEigenSolver<Mat3>(I).eigenvalues();  // ascending
  const double tol = 1e-9 * m[2];
  if (!(m[0] > 0.0)) return Refuse(where, "inertia is not positive definite (principal moments " + FormatValue(m) + ")");
  if (m[2] > m[0] + m[1] + tol) {
    return Refuse(where, "inertia breaks the triangle inequality: principal moment " + FormatValue(m[2]) +
                             " exceeds the sum of the other two " + FormatValue(m[0] + m[1]));
  }
  return Status::Ok();
}

Status CheckModel(const ModelDescription& d, ModelTree* tree) {
  const std::string model = ModelWhere(d);
  if (d.links.empty()) return Refuse(model, "has no links");
  std::map<std::string, int> link_index;
  for (size_t i = 0; i < d.links.size(); ++i) {
    const std::string where = model + ", link \"" + d.links[i].name + "\"";
    if (!link_index.emplace(d.links[i].name, static_cast<int>(i)).second) return Refuse(where, "is named twice");
    if (Status st = CheckLink(where, d.links[i]); !st.ok()) return st;
  }
  ModelTree t;
  t.parent_joint.assign(d.links.size(), -1);
  std::vector<std::vector<int>> children(d.links.size());
  std::map<std::string, int> joint_names;
  for (size_t i = 0; i < d.joints.size(); ++i) {
    const ModelJoint& j = d.joints[i];
    const std::string where = model + ", joint \"" + j.name + "\"";
    if (!joint_names.emplace(j.name, static_cast<int>(i)).second) return Refuse(where, "is named twice");
    const auto p = link_index.find(j.parent), c = link_index.find(j.child);
    if (p == link_index.end()) return Refuse(where, "names an unknown parent link \"" + j.parent + "\"");
    if (c == link_index.end()) return Refuse(where, "names an unknown child link \"" + j.child + "\"");
    if (t.parent_joint[c->second] >= 0) {
      return Refuse(where, "makes link \"" + j.child + "\" the child of a second joint (\"" +
                               d.joints[t.parent_joint[c->second]].name + "\"): a kinematic loop");
    }
    if (Status st = CheckJoint(where, j); !st.ok()) return st;
    t.parent_joint[c->second] = static_cast<int>(i);
    children[p->second].push_back(c->second);
  }
  for (size_t i = 0; i < d.links.size(); ++i) {
    if (t.parent_joint[i] >= 0) continue;
    if (t.root >= 0) {
      return Refuse(model, "has two root links, \"" + d.links[t.root].name + "\" and \"" + d.links[i].name +
                               "\": the links must form one tree");
    }
    t.root = static_cast<int>(i);
  }
  if (t.root < 0) return Refuse(model, "has no root link (every link is a joint's child): a kinematic loop");
  // breadth first from the root; a link never reached sits on a loop
  t.order.push_back(t.root);
  for (size_t k = 0; k < t.order.size(); ++k) {
    for (int c : children[t.order[k]]) t.order.push_back(c);
  }
  if (t.order.size() != d.links.size()) {
    return Refuse(model, "has links that the root \"" + d.links[t.root].name + "\" does not reach: a kinematic loop");
  }
  *tree = std::move(t);
  return Status::Ok();
}

}  // namespace contactsim::model
