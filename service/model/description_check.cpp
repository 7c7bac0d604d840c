#include "service/model/description_check.h"

#include <Eigen/Eigenvalues>

#include <map>
#include <set>
#include <sstream>

namespace contactsim::model {
namespace {

std::string Num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

std::string VecText(const Vec3& v) { return "(" + Num(v.x()) + ", " + Num(v.y()) + ", " + Num(v.z()) + ")"; }

Status CheckPose(const Pose& pose, const std::string& what, const std::string& where) {
  if (!IsFinite(pose.position) || !IsFinite(pose.orientation)) {
    return Status::InvalidArgument(where + what + " is not finite");
  }
  return Status::Ok();
}

Status CheckInertial(const Inertial& in, const std::string& where) {
  if (!std::isfinite(in.mass)) return Status::InvalidArgument(where + "mass is not finite");
  if (in.mass <= 0.0) {
    return Status::InvalidArgument(where + "mass is " + Num(in.mass) + " kg; a link's mass must be positive");
  }
  Status st = CheckPose(in.origin, "inertial origin", where);
  if (!st.ok()) return st;
  if (!in.inertia.allFinite()) return Status::InvalidArgument(where + "inertia is not finite");
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(in.inertia, Eigen::EigenvaluesOnly);
  const Vec3 m = eig.eigenvalues();  // ascending
  const double slack = kInertiaTolerance * std::abs(m.sum());
  if (m(0) <= 0.0) {
    return Status::InvalidArgument(where + "inertia is not positive definite (principal moments " + VecText(m) +
                                   " kg m^2)");
  }
  // with ascending moments, m0 + m1 >= m2 implies the other two orders
  if (m(0) + m(1) < m(2) - slack) {
    return Status::InvalidArgument(where + "inertia breaks the triangle inequality: principal moments " + VecText(m) +
                                   " kg m^2, " + Num(m(0)) + " + " + Num(m(1)) + " < " + Num(m(2)));
  }
  return Status::Ok();
}

// A collision needs a positive size to have a volume; a visual of size
// zero is only invisible (PyBullet's laikago_toes_zup.urdf draws its toes as
// spheres of radius 0), so visuals need sizes that are only not negative.
Status CheckGeometry(const Geometry& g, bool collision, const std::string& what, const std::string& where) {
  const std::string w = where + what + ": ";
  const char* need = collision ? " must be positive" : " must not be negative";
  auto bad = [collision](double v) { return !std::isfinite(v) || (collision ? !(v > 0.0) : v < 0.0); };
  switch (g.type) {
    case GeometryType::kBox:
      if (bad(g.box_size.x()) || bad(g.box_size.y()) || bad(g.box_size.z())) {
        return Status::InvalidArgument(w + "box size " + VecText(g.box_size) + need);
      }
      break;
    case GeometryType::kCylinder:
    case GeometryType::kCapsule:
      if (bad(g.length)) return Status::InvalidArgument(w + "length " + Num(g.length) + need);
      [[fallthrough]];
    case GeometryType::kSphere:
      if (bad(g.radius)) return Status::InvalidArgument(w + "radius " + Num(g.radius) + need);
      break;
    case GeometryType::kMesh:
      if (!IsFinite(g.mesh_scale) || g.mesh_scale.cwiseAbs().minCoeff() == 0.0) {
        return Status::InvalidArgument(w + "mesh scale " + VecText(g.mesh_scale) + " must be finite and non-zero");
      }
      break;
  }
  return Status::Ok();
}

Status CheckLink(const Link& link, const std::string& where) {
  if (link.inertial) {
    Status st = CheckInertial(*link.inertial, where);
    if (!st.ok()) return st;
  }
  for (size_t i = 0; i < link.collisions.size(); ++i) {
    const std::string what = "collision " + std::to_string(i);
    Status st = CheckPose(link.collisions[i].origin, what + " origin", where);
    if (st.ok()) st = CheckGeometry(link.collisions[i].geometry, true, what, where);
    if (!st.ok()) return st;
  }
  for (size_t i = 0; i < link.visuals.size(); ++i) {
    const std::string what = "visual " + std::to_string(i);
    Status st = CheckPose(link.visuals[i].origin, what + " origin", where);
    if (st.ok()) st = CheckGeometry(link.visuals[i].geometry, false, what, where);
    if (st.ok() && !link.visuals[i].rgba.allFinite()) st = Status::InvalidArgument(where + what + " rgba is not finite");
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

Status CheckJoint(ModelJoint* joint, const std::string& where) {
  Status st = CheckPose(joint->origin, "origin", where);
  if (!st.ok()) return st;
  if (HasAxis(joint->type)) {
    const double n = joint->axis.norm();
    if (!std::isfinite(n) || n == 0.0) {
      return Status::InvalidArgument(where + "axis " + VecText(joint->axis) + " must be finite and non-zero");
    }
    joint->axis /= n;
  }
  if (joint->limits) {
    const JointLimits& l = *joint->limits;
    if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || !std::isfinite(l.effort) ||
        !std::isfinite(l.velocity)) {
      return Status::InvalidArgument(where + "limit is not finite");
    }
    if (l.lower > l.upper) {
      return Status::InvalidArgument(where + "limit lower " + Num(l.lower) + " is above upper " + Num(l.upper));
    }
    if (l.effort < 0.0 || l.velocity < 0.0) {
      return Status::InvalidArgument(where + "limit effort " + Num(l.effort) + " and velocity " + Num(l.velocity) +
                                     " must not be negative");
    }
  }
  if (!std::isfinite(joint->damping) || !std::isfinite(joint->friction) || joint->damping < 0.0 ||
      joint->friction < 0.0) {
    return Status::InvalidArgument(where + "dynamics damping " + Num(joint->damping) + " and friction " +
                                   Num(joint->friction) + " must be finite and not negative");
  }
  return Status::Ok();
}

// The cycle of parents through `start`, a link the root does not reach.
std::string ParentCycle(const std::string& start, const std::map<std::string, std::string>& parent_of) {
  std::string link = start;
  std::set<std::string> seen;
  while (seen.insert(link).second) link = parent_of.at(link);  // every link here has a parent
  std::string cycle = link;
  for (std::string l = parent_of.at(link); ; l = parent_of.at(l)) {
    cycle = l + " -> " + cycle;
    if (l == link) break;
  }
  return cycle;
}

}  // namespace

bool HasAxis(JointType type) {
  return type == JointType::kRevolute || type == JointType::kContinuous || type == JointType::kPrismatic ||
         type == JointType::kPlanar;
}

Status CheckFileSize(const std::string& text, const std::string& source_path, const ReadLimits& limits,
                     SourceMap* where) {
  where->file = source_path.empty() ? "<inline>" : source_path;
  if (text.size() <= limits.max_file_bytes) return Status::Ok();
  return Status::ResourceExhausted(where->File() + std::to_string(text.size()) + " bytes, over the limit of " +
                                   std::to_string(limits.max_file_bytes) + " (max_file_bytes)");
}

Status CheckCounts(size_t links, size_t joints, const ReadLimits& limits, const SourceMap& where) {
  if (links > limits.max_links) {
    return Status::ResourceExhausted(where.File() + std::to_string(links) + " links, over the limit of " +
                                     std::to_string(limits.max_links) + " (max_links)");
  }
  if (joints > limits.max_joints) {
    return Status::ResourceExhausted(where.File() + std::to_string(joints) + " joints, over the limit of " +
                                     std::to_string(limits.max_joints) + " (max_joints)");
  }
  return Status::Ok();
}

Status CheckTree(const SourceMap& where, ModelDescription* model) {
  if (model->links.empty()) return Status::InvalidArgument(where.File() + "the model has no links");
  std::set<std::string> links, joints;
  for (const Link& l : model->links) {
    if (!links.insert(l.name).second) return Status::InvalidArgument(where.Link(l.name) + "a second link of this name");
  }
  std::map<std::string, std::string> parent_of;
  std::map<std::string, std::vector<std::string>> children;
  for (const ModelJoint& j : model->joints) {
    const std::string w = where.Joint(j.name);
    if (!joints.insert(j.name).second) return Status::InvalidArgument(w + "a second joint of this name");
    if (!links.count(j.parent)) return Status::InvalidArgument(w + "parent link '" + j.parent + "' is not in the model");
    if (!links.count(j.child)) return Status::InvalidArgument(w + "child link '" + j.child + "' is not in the model");
    if (j.parent == j.child) return Status::InvalidArgument(w + "joins link '" + j.child + "' to itself");
    if (parent_of.count(j.child)) {
      return Status::InvalidArgument(w + "link '" + j.child + "' already has parent '" + parent_of[j.child] +
                                     "': a kinematic loop (a link may be the child of one joint only)");
    }
    parent_of[j.child] = j.parent;
    children[j.parent].push_back(j.child);
  }
  std::vector<std::string> roots;
  for (const Link& l : model->links) {
    if (!parent_of.count(l.name)) roots.push_back(l.name);
  }
  if (roots.empty()) {
    return Status::InvalidArgument(where.File() + "a kinematic loop: " + ParentCycle(model->links[0].name, parent_of) +
                                   " (every link has a parent, so there is no root)");
  }
  if (roots.size() > 1) {
    return Status::InvalidArgument(where.File() + std::to_string(roots.size()) + " root links ('" + roots[0] +
                                   "', '" + roots[1] + "', ...): the links must form one tree joined by joints");
  }
  std::set<std::string> reached{roots[0]};
  std::vector<std::string> stack{roots[0]};
  while (!stack.empty()) {
    const std::string l = stack.back();
    stack.pop_back();
    for (const std::string& c : children[l]) {
      if (reached.insert(c).second) stack.push_back(c);
    }
  }
  for (const Link& l : model->links) {
    if (!reached.count(l.name)) {
      return Status::InvalidArgument(where.File() + "a kinematic loop: " + ParentCycle(l.name, parent_of));
    }
  }
  model->root_link = roots[0];
  return Status::Ok();
}

Status CheckValues(const SourceMap& where, ModelDescription* model) {
  for (const Link& l : model->links) {
    Status st = CheckLink(l, where.Link(l.name));
    if (!st.ok()) return st;
  }
  for (ModelJoint& j : model->joints) {
    Status st = CheckJoint(&j, where.Joint(j.name));
    if (!st.ok()) return st;
  }
  return CheckMimics(where, *model);
}

}  // namespace contactsim::model
