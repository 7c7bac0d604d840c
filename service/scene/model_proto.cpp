#include "service/scene/model_proto.h"

#include <google/protobuf/repeated_field.h>

#include "service/model/visual_entry.h"

namespace contactsim {
namespace {

using model::Geometry;
using model::GeometryType;
using model::JointType;
using model::Pose;
using Doubles = google::protobuf::RepeatedField<double>;

void Put(const Vec3& v, Doubles* out) { out->Add(v.data(), v.data() + 3); }
void Put(const Quat& q, Doubles* out) {
  for (double c : {q.w(), q.x(), q.y(), q.z()}) out->Add(c);
}

Status Size(const std::string& where, const Doubles& v, int n) {
  if (v.size() == n) return Status::Ok();
  return Status::InvalidArgument(where + " has " + std::to_string(v.size()) + " numbers, not " + std::to_string(n));
}

Vec3 V3(const Doubles& v, int at = 0) { return Vec3(v[at], v[at + 1], v[at + 2]); }
Quat Q(const Doubles& v) { return Quat(v[0], v[1], v[2], v[3]); }

void SavePose(const Pose& p, proto::ModelPose* out) {
  Put(p.position, out->mutable_position());
  Put(p.orientation, out->mutable_orientation());
}

Status LoadPose(const std::string& where, const proto::ModelPose& in, Pose* p) {
  Status st = Size(where + " position", in.position(), 3);
  if (st.ok()) st = Size(where + " orientation", in.orientation(), 4);
  if (!st.ok()) return st;
  p->position = V3(in.position());
  p->orientation = Q(in.orientation());
  return Status::Ok();
}

void SaveGeometry(const Geometry& g, proto::ModelGeometry* out) {
  out->set_type(static_cast<int>(g.type));
  Put(g.box_size, out->mutable_box_size());
  out->set_radius(g.radius);
  out->set_length(g.length);
  out->set_mesh_path(g.mesh_path);
  Put(g.mesh_scale, out->mutable_mesh_scale());
  for (const Vec3& v : g.mesh_vertices) Put(v, out->mutable_mesh_vertices());
}

Status LoadGeometry(const std::string& where, const proto::ModelGeometry& in, Geometry* g) {
  if (in.type() < 0 || in.type() > static_cast<int>(GeometryType::kMesh)) {
    return Status::InvalidArgument(where + ": unknown geometry type " + std::to_string(in.type()));
  }
  Status st = Size(where + " box_size", in.box_size(), 3);
  if (st.ok()) st = Size(where + " mesh_scale", in.mesh_scale(), 3);
  if (st.ok() && in.mesh_vertices_size() % 3 != 0) st = Status::InvalidArgument(where + " mesh_vertices: not x y z triples");
  if (!st.ok()) return st;
  g->type = static_cast<GeometryType>(in.type());
  g->box_size = V3(in.box_size());
  g->radius = in.radius();
  g->length = in.length();
  g->mesh_path = in.mesh_path();
  g->mesh_scale = V3(in.mesh_scale());
  g->mesh_vertices.clear();
  for (int i = 0; i < in.mesh_vertices_size(); i += 3) g->mesh_vertices.push_back(V3(in.mesh_vertices(), i));
  return Status::Ok();
}

void SaveVisual(const model::VisualElement& v, proto::ModelVisual* out) {
  out->set_name(v.name);
  SavePose(v.origin, out->mutable_origin());
  SaveGeometry(v.geometry, out->mutable_geometry());
  out->mutable_rgba()->Add(v.rgba.data(), v.rgba.data() + 4);
}

Status LoadVisual(const std::string& where, const proto::ModelVisual& in, model::VisualElement* v) {
  v->name = in.name();
  Status st = LoadPose(where + " visual", in.origin(), &v->origin);
  if (st.ok()) st = LoadGeometry(where + " visual", in.geometry(), &v->geometry);
  if (st.ok()) st = Size(where + " visual rgba", in.rgba(), 4);
  if (!st.ok()) return st;
  v->rgba = Eigen::Vector4d(in.rgba(0), in.rgba(1), in.rgba(2), in.rgba(3));
  return Status::Ok();
}

void SaveLink(const model::Link& l, proto::ModelLink* out) {
  out->set_name(l.name);
  if (l.inertial) {
    proto::ModelInertial* in = out->mutable_inertial();
    in->set_mass(l.inertial->mass);
    SavePose(l.inertial->origin, in->mutable_origin());
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) in->add_inertia(l.inertial->inertia(r, c));
    }
  }
  for (const model::CollisionElement& c : l.collisions) {
    proto::ModelCollision* pc = out->add_collisions();
    pc->set_name(c.name);
    SavePose(c.origin, pc->mutable_origin());
    SaveGeometry(c.geometry, pc->mutable_geometry());
  }
  for (const model::VisualElement& v : l.visuals) SaveVisual(v, out->add_visuals());
}

Status LoadLink(const proto::ModelLink& in, model::Link* l) {
  const std::string where = "link \"" + in.name() + "\"";
  l->name = in.name();
  Status st;
  if (in.has_inertial()) {
    model::Inertial i;
    i.mass = in.inertial().mass();
    if (!(st = LoadPose(where + " inertial", in.inertial().origin(), &i.origin)).ok()) return st;
    if (!(st = Size(where + " inertia", in.inertial().inertia(), 9)).ok()) return st;
    for (int k = 0; k < 9; ++k) i.inertia(k / 3, k % 3) = in.inertial().inertia(k);
    l->inertial = i;
  }
  for (const proto::ModelCollision& pc : in.collisions()) {
    model::CollisionElement c;
    c.name = pc.name();
    if (!(st = LoadPose(where + " collision", pc.origin(), &c.origin)).ok()) return st;
    if (!(st = LoadGeometry(where + " collision", pc.geometry(), &c.geometry)).ok()) return st;
    l->collisions.push_back(std::move(c));
  }
  for (const proto::ModelVisual& pv : in.visuals()) {
    l->visuals.emplace_back();
    if (!(st = LoadVisual(where, pv, &l->visuals.back())).ok()) return st;
  }
  return Status::Ok();
}

void SaveJoint(const model::ModelJoint& j, proto::ModelJointSpec* out) {
  out->set_name(j.name);
  out->set_type(static_cast<int>(j.type));
  out->set_parent(j.parent);
  out->set_child(j.child);
  SavePose(j.origin, out->mutable_origin());
  Put(j.axis, out->mutable_axis());
  if (j.limits) {
    proto::ModelJointLimits* l = out->mutable_limits();
    l->set_lower(j.limits->lower);
    l->set_upper(j.limits->upper);
    l->set_effort(j.limits->effort);
    l->set_velocity(j.limits->velocity);
  }
  out->set_damping(j.damping);
  out->set_friction(j.friction);
  if (j.mimic) {
    proto::ModelMimic* m = out->mutable_mimic();
    m->set_joint(j.mimic->joint);
    m->set_multiplier(j.mimic->multiplier);
    m->set_offset(j.mimic->offset);
  }
}

Status LoadJoint(const proto::ModelJointSpec& in, model::ModelJoint* j) {
  const std::string where = "joint \"" + in.name() + "\"";
  if (in.type() < 0 || in.type() > static_cast<int>(JointType::kPlanar)) {
    return Status::InvalidArgument(where + ": unknown joint type " + std::to_string(in.type()));
  }
  j->name = in.name();
  j->type = static_cast<JointType>(in.type());
  j->parent = in.parent();
  j->child = in.child();
  Status st = LoadPose(where, in.origin(), &j->origin);
  if (st.ok()) st = Size(where + " axis", in.axis(), 3);
  if (!st.ok()) return st;
  j->axis = V3(in.axis());
  if (in.has_limits()) {
    j->limits = model::JointLimits{in.limits().lower(), in.limits().upper(), in.limits().effort(),
                                   in.limits().velocity()};
  }
  j->damping = in.damping();
  j->friction = in.friction();
  // checked with the rest of the description (CheckMimics)
  if (in.has_mimic()) j->mimic = model::ModelMimic{in.mimic().joint(), in.mimic().multiplier(), in.mimic().offset()};
  return Status::Ok();
}

}  // namespace

void SaveModelDescription(const model::ModelDescription& d, proto::ModelDescription* out) {
  out->set_name(d.name);
  out->set_source(d.source);
  for (const model::Link& l : d.links) SaveLink(l, out->add_links());
  for (const model::ModelJoint& j : d.joints) SaveJoint(j, out->add_joints());
  out->set_self_collide(d.self_collide);
  out->set_root_link(d.root_link);
}

Status LoadModelDescription(const proto::ModelDescription& in, model::ModelDescription* d) {
  model::ModelDescription m;
  m.name = in.name();
  m.source = in.source();
  m.self_collide = in.self_collide();
  m.root_link = in.root_link();
  Status st;
  for (const proto::ModelLink& pl : in.links()) {
    m.links.emplace_back();
    if (!(st = LoadLink(pl, &m.links.back())).ok()) return st;
  }
  for (const proto::ModelJointSpec& pj : in.joints()) {
    m.joints.emplace_back();
    if (!(st = LoadJoint(pj, &m.joints.back())).ok()) return st;
  }
  *d = std::move(m);
  return Status::Ok();
}

void SaveModelRecord(const ModelRecord& r, proto::ModelRecord* out) {
  out->set_id(r.id);
  out->set_name(r.name);
  out->set_source(r.source);
  out->set_fixed_base(r.fixed_base);
  out->set_self_collide(r.self_collide);
  for (const ModelLinkEntry& l : r.links) {
    proto::ModelLinkEntry* pl = out->add_links();
    pl->set_name(l.name);
    pl->set_body(l.body);
    Put(l.position, pl->mutable_position());
    Put(l.orientation, pl->mutable_orientation());
    // the record keeps no mesh vertices: a viewer reads the mesh file
    for (const ModelVisualEntry& v : l.visuals) SaveVisual(model::FromVisualEntry(v), pl->add_visuals());
  }
  for (const ModelJointEntry& j : r.joints) {
    proto::ModelJointEntry* pj = out->add_joints();
    pj->set_name(j.name);
    pj->set_type(j.type);
    pj->set_joint(j.joint);
    pj->set_damping(j.damping);
    pj->set_friction(j.friction);
    pj->set_effort_limit(j.effort_limit);
    pj->set_velocity_limit(j.velocity_limit);
  }
}

Status LoadModelRecord(const proto::ModelRecord& in, ModelRecord* r) {
  ModelRecord m;
  m.id = in.id();
  m.name = in.name();
  m.source = in.source();
  m.fixed_base = in.fixed_base();
  m.self_collide = in.self_collide();
  Status st;
  for (const proto::ModelLinkEntry& pl : in.links()) {
    const std::string where = "model \"" + m.name + "\" link \"" + pl.name() + "\"";
    if (!(st = Size(where + " position", pl.position(), 3)).ok()) return st;
    if (!(st = Size(where + " orientation", pl.orientation(), 4)).ok()) return st;
    m.links.push_back({pl.name(), pl.body(), V3(pl.position()), Q(pl.orientation()), {}});
    for (const proto::ModelVisual& pv : pl.visuals()) {
      model::VisualElement v;
      if (!(st = LoadVisual(where, pv, &v)).ok()) return st;
      m.links.back().visuals.push_back(model::ToVisualEntry(v));
    }
  }
  for (const proto::ModelJointEntry& pj : in.joints()) {
    m.joints.push_back({pj.name(), pj.type(), pj.joint(), pj.damping(), pj.friction(), pj.effort_limit(),
                        pj.velocity_limit()});
  }
  *r = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
