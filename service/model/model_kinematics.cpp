#include "service/model/model_kinematics.h"

#include <map>
#include <string>

namespace contactsim::model {
namespace {

// The child frame in the joint's frame for its coordinates at `q`.
Pose JointMotion(const ModelJoint& joint, const double* q) {
  Pose m;
  switch (joint.type) {
    case JointType::kRevolute:
    case JointType::kContinuous:
      m.orientation = QuatFromRotationVector(q[0] * joint.axis);
      break;
    case JointType::kPrismatic:
      m.position = q[0] * joint.axis;
      break;
    case JointType::kFixed:
      break;
    case JointType::kFloating:
      m.position = Vec3(q[0], q[1], q[2]);
      m.orientation = Quat(q[3], q[4], q[5], q[6]).normalized();
      break;
    case JointType::kPlanar: {
      Vec3 t1, t2;
      PerpendicularBasis(joint.axis, &t1, &t2);
      m.position = q[0] * t1 + q[1] * t2;
      m.orientation = QuatFromRotationVector(q[2] * joint.axis);
      break;
    }
  }
  return m;
}

}  // namespace

int JointCoordinateCount(JointType type) {
  switch (type) {
    case JointType::kRevolute:
    case JointType::kContinuous:
    case JointType::kPrismatic:
      return 1;
    case JointType::kFixed:
      return 0;
    case JointType::kPlanar:
      return 3;
    case JointType::kFloating:
      return 7;
  }
  return 0;
}

int ModelCoordinateCount(const ModelDescription& model) {
  int n = 0;
  for (const ModelJoint& j : model.joints) n += JointCoordinateCount(j.type);
  return n;
}

Pose Compose(const Pose& a, const Pose& b) {
  Pose out;
  out.position = a.position + a.orientation * b.position;
  out.orientation = (a.orientation * b.orientation).normalized();
  return out;
}

Pose InversePose(const Pose& a) {
  Pose out;
  out.orientation = a.orientation.conjugate();
  out.position = -(out.orientation * a.position);
  return out;
}

Status LinkWorldPoses(const ModelDescription& model, const Pose& root, const std::vector<double>& q,
                      std::vector<Pose>* poses) {
  const int n = ModelCoordinateCount(model);
  if (static_cast<int>(q.size()) != n) {
    return Status::InvalidArgument("model '" + model.name + "' takes " + std::to_string(n) +
                                   " joint coordinates, got " + std::to_string(q.size()));
  }
  for (double v : q) {
    if (!std::isfinite(v)) return Status::InvalidArgument("a joint coordinate is not finite");
  }
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < model.links.size(); ++i) index[model.links[i].name] = i;
  // the joint that makes each link a child, and where its coordinates start
  std::vector<const ModelJoint*> parent_joint(model.links.size(), nullptr);
  std::vector<size_t> offset(model.links.size(), 0);
  std::vector<std::vector<size_t>> children(model.links.size());
  size_t at = 0;
  for (const ModelJoint& j : model.joints) {
    const size_t child = index.at(j.child);
    parent_joint[child] = &j;
    offset[child] = at;
    children[index.at(j.parent)].push_back(child);
    at += JointCoordinateCount(j.type);
  }
  std::vector<Pose> out(model.links.size());
  std::vector<size_t> stack{index.at(model.root_link)};
  out[stack[0]] = root;
  while (!stack.empty()) {
    const size_t parent = stack.back();
    stack.pop_back();
    for (size_t c : children[parent]) {
      const ModelJoint& j = *parent_joint[c];
      out[c] = Compose(Compose(out[parent], j.origin), JointMotion(j, q.data() + offset[c]));
      stack.push_back(c);
    }
  }
  *poses = std::move(out);
  return Status::Ok();
}

}  // namespace contactsim::model
