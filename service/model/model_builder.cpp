#include "service/model/model_builder.h"

#include "service/model/body_plan.h"
#include "service/model/engine_settings.h"
#include "service/model/model_check.h"
#include "service/model/visual_entry.h"
#include "service/physics/hull_memo.h"

namespace contactsim::model {
namespace {

// Every joint at its zero: 0 for the moving ones, the identity pose for a
// floating one (x, y, z, qw, qx, qy, qz).
std::vector<double> ZeroCoordinates(const ModelDescription& d) {
  std::vector<double> q;
  for (const ModelJoint& j : d.joints) {
    if (j.type == JointType::kFloating) {
      q.insert(q.end(), {0, 0, 0, 1, 0, 0, 0});
    } else {
      q.insert(q.end(), JointCoordinateCount(j.type), 0.0);
    }
  }
  return q;
}

ModelRecord MakeRecord(const ModelDescription& d, const ModelOptions& o) {
  ModelRecord r;
  r.name = o.name.empty() ? d.name : o.name;
  r.source = d.source;
  r.fixed_base = o.fixed_base;
  r.self_collide = o.self_collide;
  for (const Link& l : d.links) {
    ModelLinkEntry e{l.name, 0, Vec3::Zero(), Quat::Identity(), {}};
    for (const VisualElement& v : l.visuals) e.visuals.push_back(ToVisualEntry(v));
    r.links.push_back(std::move(e));
  }
  for (const ModelJoint& j : d.joints) {
    ModelJointEntry e;
    e.name = j.name;
    e.type = JointTypeName(j.type);
    e.damping = j.damping;
    e.friction = j.friction;
    if (j.limits) {
      e.effort_limit = j.limits->effort;
      e.velocity_limit = j.limits->velocity;
    }
    r.joints.push_back(std::move(e));
  }
  return r;
}

}  // namespace

Status BuildModel(ModelDescription d, const ModelOptions& options, ModelBuild* build) {
  ModelTree tree;
  if (Status st = CheckModel(&d, &tree); !st.ok()) return st;
  const std::string model = ModelWhere(d);
  if (!options.base.position.allFinite() || !options.base.orientation.coeffs().allFinite() ||
      std::abs(options.base.orientation.norm() - 1.0) > 1e-6) {
    return Status::InvalidArgument(model + ": the base pose must be finite with a unit orientation");
  }
  if (Status st = CheckMaxHullVertices(options.max_hull_vertices); !st.ok()) return st.Prefixed(model + ": ");
  ModelBuild b;
  std::vector<BodyPlan> plans;
  std::vector<Pose> link_in_body;
  PlanBodies(d, tree, &plans, &b.link_body, &link_in_body);
  // every link's pose with every joint at zero (forward kinematics)
  if (Status st = LinkWorldPoses(d, options.base, ZeroCoordinates(d), &b.link_pose_W); !st.ok()) {
    return st.Prefixed(model + ": ");
  }
  HullMemo memo;  // links that share a mesh budget it once
  for (const BodyPlan& plan : plans) {
    const std::string where = model + ", link \"" + d.links[plan.owner].name + "\"";
    const bool is_static = options.fixed_base && plan.owner == tree.root;
    BuiltBody body;
    body.link = plan.owner;
    if (Status st = MakeBodySettings(plan, b.link_pose_W[plan.owner], is_static, options.max_hull_vertices, where,
                                     &memo, &body.settings);
        !st.ok()) {
      return st;
    }
    body.settings.name = (options.name.empty() ? d.name : options.name) + "/" + d.links[plan.owner].name;
    b.bodies.push_back(std::move(body));
  }
  for (size_t ji = 0; ji < d.joints.size(); ++ji) {
    const ModelJoint& j = d.joints[ji];
    if (j.type == JointType::kFixed || j.type == JointType::kFloating) continue;  // merged, or free
    const std::string where = model + ", joint \"" + j.name + "\"";
    int child = -1;
    for (size_t k = 0; k < d.links.size(); ++k) {
      if (tree.parent_joint[k] == static_cast<int>(ji)) child = static_cast<int>(k);
    }
    const int parent = tree.parent_link[child];
    BuiltJoint bj;
    bj.joint = static_cast<int>(ji);
    bj.body_a = b.link_body[parent];
    bj.body_b = b.link_body[child];
    if (Status st = MakeJointSettings(j, b.link_pose_W[child], where, &bj.settings); !st.ok()) return st;
    bj.actuator = MakeJointActuator(j);
    b.joints.push_back(std::move(bj));
  }
  // CheckMimics has made every master a joint with a coordinate, so built
  for (BuiltJoint& bj : b.joints) {
    const ModelJoint& j = d.joints[bj.joint];
    if (!j.mimic) continue;
    for (size_t k = 0; k < b.joints.size(); ++k) {
      if (d.joints[b.joints[k].joint].name == j.mimic->joint) bj.mimic_of = static_cast<int>(k);
    }
    bj.mimic.multiplier = j.mimic->multiplier;
    bj.mimic.offset = j.mimic->offset;
  }
  b.record = MakeRecord(d, options);
  *build = std::move(b);
  return Status::Ok();
}

}  // namespace contactsim::model
