#include "service/scene/snapshot.h"


#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "service/collision/height_field.h"
#include "service/collision/triangle_mesh.h"
#include "service/physics/body_settings.h"
#include "service/physics/convex_hull.h"
#include "service/scene/proto_text.h"
#include "service/scene/snapshot_sensors.h"
#include "service/scene/model_proto.h"

namespace contactsim {
namespace {

using google::protobuf::RepeatedField;

template <typename Derived>
void PutAll(const Eigen::MatrixBase<Derived>& m, RepeatedField<double>* out) {
  // row-major for matrices, so a reader needs no Eigen convention
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) out->Add(m(r, c));
}

// Reads exactly rows x cols numbers into m, or names the field.
template <typename Derived>
Status GetAll(const RepeatedField<double>& in, const std::string& field, Eigen::MatrixBase<Derived>* m) {
  if (in.size() != m->rows() * m->cols()) {
    return Status::InvalidArgument("snapshot: " + field + " must hold " + std::to_string(m->rows() * m->cols()) +
                                   " numbers, got " + std::to_string(in.size()));
  }
  int k = 0;
  for (int r = 0; r < m->rows(); ++r)
    for (int c = 0; c < m->cols(); ++c) (*m)(r, c) = in.Get(k++);
  return Status::Ok();
}

void SaveHull(const ConvexHull& hull, proto::SnapshotHull* out) {
  for (const Vec3& v : hull.vertices) PutAll(v, out->mutable_vertices());
  for (const ConvexHull::Face& f : hull.faces) {
    proto::SnapshotHull::Face* pf = out->add_faces();
    PutAll(f.normal, pf->mutable_normal());
    pf->set_offset(f.offset);
    for (int i : f.vertices) pf->add_vertices(i);
  }
  for (const auto& e : hull.edges) {
    out->add_edges(e[0]);
    out->add_edges(e[1]);
  }
}

Status LoadHull(const proto::SnapshotHull& in, const std::string& where, std::shared_ptr<const ConvexHull>* out) {
  auto hull = std::make_shared<ConvexHull>();
  const int nv = in.vertices_size() / 3;
  if (in.vertices_size() % 3 != 0 || nv < 4 || in.edges_size() % 2 != 0 || in.faces_size() < 4) {
    return Status::InvalidArgument("snapshot: " + where + " hull needs >= 4 vertices (x y z), >= 4 faces and edge pairs");
  }
  auto index_ok = [nv](int i) { return i >= 0 && i < nv; };
  for (int i = 0; i < nv; ++i) hull->vertices.emplace_back(in.vertices(3 * i), in.vertices(3 * i + 1), in.vertices(3 * i + 2));
  for (const auto& pf : in.faces()) {
    ConvexHull::Face f;
    Status st = GetAll(pf.normal(), where + " hull face normal", &f.normal);
    if (!st.ok()) return st;
    f.offset = pf.offset();
    for (int i : pf.vertices()) {
      if (!index_ok(i)) return Status::InvalidArgument("snapshot: " + where + " hull face vertex " + std::to_string(i) + " out of range");
      f.vertices.push_back(i);
    }
    hull->faces.push_back(std::move(f));
  }
  for (int i = 0; i + 1 < in.edges_size(); i += 2) {
    if (!index_ok(in.edges(i)) || !index_ok(in.edges(i + 1))) {
      return Status::InvalidArgument("snapshot: " + where + " hull edge vertex out of range");
    }
    hull->edges.push_back({in.edges(i), in.edges(i + 1)});
  }
  *out = std::move(hull);
  return Status::Ok();
}

Status LoadSleep(const proto::SnapshotSleep& in, SleepSettings* out) {
  const SleepSettings s{in.enabled(), in.linear_speed(), in.angular_speed(), in.time_to_sleep()};
  for (const auto& [name, value] : {std::pair<const char*, double>{"linear_speed", s.linear_speed},
                                    {"angular_speed", s.angular_speed}, {"time_to_sleep", s.time_to_sleep}}) {
    if (!(value >= 0.0 && value < 1e300)) {
      return Status::InvalidArgument(std::string("snapshot: sleep ") + name + " must be finite and >= 0, got " +
                                     std::to_string(value));
    }
  }
  *out = s;
  return Status::Ok();
}

// A mesh's vertices and triangles as built, or a heightfield's grid.
void SaveSurface(const Shape& shape, proto::SnapshotShape* s) {
  if (shape.mesh) {
    for (const Vec3& v : shape.mesh->vertices) PutAll(v, s->mutable_mesh_vertices());
    for (const auto& t : shape.mesh->triangles) {
      for (int k : t) s->add_mesh_indices(k);
    }
  }
  if (shape.heightfield) {
    const HeightField& f = *shape.heightfield;
    s->set_height_rows(f.rows);
    s->set_height_cols(f.cols);
    for (double h : f.heights) s->add_heights(h);
    s->set_height_spacing_x(f.spacing_x);
    s->set_height_spacing_y(f.spacing_y);
  }
}

// The inverse of SaveSurface, through the same builders and checks as a command's.
Status LoadSurface(const proto::SnapshotShape& s, const std::string& where, Shape* out) {
  Status st;
  if (out->type == ShapeType::kMesh) {
    if (s.mesh_vertices_size() % 3 != 0) {
      return Status::InvalidArgument("snapshot: " + where + " mesh_vertices must be x y z per vertex, got " +
                                     std::to_string(s.mesh_vertices_size()) + " values");
    }
    std::vector<Vec3> vertices;
    for (int i = 0; i + 2 < s.mesh_vertices_size(); i += 3) {
      vertices.emplace_back(s.mesh_vertices(i), s.mesh_vertices(i + 1), s.mesh_vertices(i + 2));
    }
    const std::vector<int> indices(s.mesh_indices().begin(), s.mesh_indices().end());
    st = BuildTriangleMesh(vertices, indices, 1.0, &out->mesh);
  } else if (out->type == ShapeType::kHeightfield) {
    const std::vector<double> heights(s.heights().begin(), s.heights().end());
    st = BuildHeightField(s.height_rows(), s.height_cols(), heights, s.height_spacing_x(), s.height_spacing_y(),
                          &out->heightfield);
  }
  return st.ok() ? st : Status::InvalidArgument("snapshot: " + where + " " + st.message());
}

// A shape and, for a compound, its children with their poses as stored.
void SaveShape(const Shape& shape, proto::SnapshotShape* s) {
  s->set_type(static_cast<int>(shape.type));
  s->set_radius(shape.radius);
  PutAll(shape.half_extents, s->mutable_half_extents());
  s->set_half_length(shape.half_length);
  PutAll(shape.plane_normal, s->mutable_plane_normal());
  s->set_plane_offset(shape.plane_offset);
  if (shape.hull) SaveHull(*shape.hull, s->mutable_hull());
  SaveSurface(shape, s);
  if (!shape.compound) return;
  for (const ShapeChild& child : shape.compound->children) {
    proto::SnapshotChild* c = s->add_children();
    SaveShape(child.shape, c->mutable_shape());
    PutAll(child.position, c->mutable_position());
    for (double v : {child.orientation.w(), child.orientation.x(), child.orientation.y(), child.orientation.z()}) {
      c->add_orientation(v);
    }
  }
}

// The inverse of SaveShape; a child may be any shape but a plane or a
// compound (`compound_ok` false), as CreateBody builds them.
Status LoadShape(const proto::SnapshotShape& s, const std::string& where, bool compound_ok, Shape* shape) {
  const int last = static_cast<int>(ShapeType::kCount) - 1;
  if (s.type() < 0 || s.type() > last) {
    return Status::InvalidArgument("snapshot: " + where + " shape type must be in [0, " + std::to_string(last) +
                                   "], got " + std::to_string(s.type()));
  }
  Shape out;
  out.type = static_cast<ShapeType>(s.type());
  if (!compound_ok && (out.type == ShapeType::kCompound || out.type == ShapeType::kPlane || out.IsTriangleSurface())) {
    return Status::InvalidArgument("snapshot: " + where + " must be a sphere, box, capsule or convex, got " +
                                   ShapeTypeName(out.type));
  }
  out.radius = s.radius();
  out.half_length = s.half_length();
  out.plane_offset = s.plane_offset();
  Status st;
  if (!(st = GetAll(s.half_extents(), where + " half_extents", &out.half_extents)).ok()) return st;
  if (!(st = GetAll(s.plane_normal(), where + " plane_normal", &out.plane_normal)).ok()) return st;
  if (out.type == ShapeType::kConvex && !(st = LoadHull(s.hull(), where, &out.hull)).ok()) return st;
  if (out.IsTriangleSurface() && !(st = LoadSurface(s, where, &out)).ok()) return st;
  if (out.type == ShapeType::kCompound) {
    if (s.children_size() < 1 || s.children_size() > kMaxShapeParts) {
      return Status::InvalidArgument("snapshot: " + where + " compound must hold 1 to " +
                                     std::to_string(kMaxShapeParts) + " children, got " +
                                     std::to_string(s.children_size()));
    }
    std::vector<ShapeChild> children(s.children_size());
    for (int k = 0; k < s.children_size(); ++k) {
      const std::string child = where + " child " + std::to_string(k);
      const proto::SnapshotChild& c = s.children(k);
      Eigen::Vector4d q;
      if (!(st = LoadShape(c.shape(), child, false, &children[k].shape)).ok()) return st;
      if (!(st = GetAll(c.position(), child + " position", &children[k].position)).ok()) return st;
      if (!(st = GetAll(c.orientation(), child + " orientation", &q)).ok()) return st;
      children[k].orientation = Quat(q[0], q[1], q[2], q[3]);  // as stored, bit for bit
    }
    out.compound = Shape::Compound(std::move(children)).compound;
  }
  *shape = std::move(out);
  return Status::Ok();
}

void SaveBody(const RigidBody& b, proto::SnapshotBody* out) {
  out->set_id(b.id);
  out->set_name(b.name);
  SaveShape(b.shape, out->mutable_shape());
  if (!b.frame_origin.isZero(0.0)) PutAll(b.frame_origin, out->mutable_frame_origin());
  if (b.explicit_inertia) out->set_explicit_inertia(true);
  out->set_restitution(b.material.restitution);
  out->set_friction(b.material.friction);
  out->set_motion(static_cast<int>(b.motion));
  out->set_mass(b.mass);
  out->set_inv_mass(b.inv_mass);
  PutAll(b.inertia_body, out->mutable_inertia_body());
  PutAll(b.inv_inertia_body, out->mutable_inv_inertia_body());
  PutAll(b.x, out->mutable_x());
  for (double c : {b.q.w(), b.q.x(), b.q.y(), b.q.z()}) out->add_q(c);
  PutAll(b.P, out->mutable_linear_momentum());
  PutAll(b.L, out->mutable_angular_momentum());
  PutAll(b.force, out->mutable_force());
  PutAll(b.torque, out->mutable_torque());
  PutAll(b.kinematic_v, out->mutable_kinematic_v());
  PutAll(b.kinematic_w, out->mutable_kinematic_w());
  out->set_rest_time(b.rest_time);
  out->set_sleep_island(b.sleep_island);
  if (!HasDefaultFilter(b)) {  // a default filter leaves the bytes as before filters existed
    out->set_collision_category(b.collision_category);
    out->set_collision_mask(b.collision_mask);
    out->set_collision_group(b.collision_group);
  }
}

Status LoadBody(const proto::SnapshotBody& in, RigidBody* b) {
  const std::string where = "body " + std::to_string(in.id());
  b->id = in.id();
  b->name = in.name();
  Status st;
  if (!(st = LoadShape(in.shape(), where, true, &b->shape)).ok()) return st;
  b->frame_origin.setZero();
  if (in.frame_origin_size() > 0 && !(st = GetAll(in.frame_origin(), where + " frame_origin", &b->frame_origin)).ok()) {
    return st;
  }
  b->explicit_inertia = in.explicit_inertia();
  if (in.motion() < 0 || in.motion() > static_cast<int>(MotionType::kKinematic)) {
    return Status::InvalidArgument("snapshot: " + where + " motion must be 0, 1 or 2, got " + std::to_string(in.motion()));
  }
  b->material = {in.restitution(), in.friction()};
  b->motion = static_cast<MotionType>(in.motion());
  b->mass = in.mass();
  b->inv_mass = in.inv_mass();
  Eigen::Vector4d q;
  if (!(st = GetAll(in.inertia_body(), where + " inertia_body", &b->inertia_body)).ok()) return st;
  if (!(st = GetAll(in.inv_inertia_body(), where + " inv_inertia_body", &b->inv_inertia_body)).ok()) return st;
  if (!(st = GetAll(in.x(), where + " x", &b->x)).ok()) return st;
  if (!(st = GetAll(in.q(), where + " q", &q)).ok()) return st;
  if (!(st = GetAll(in.linear_momentum(), where + " linear_momentum", &b->P)).ok()) return st;
  if (!(st = GetAll(in.angular_momentum(), where + " angular_momentum", &b->L)).ok()) return st;
  if (!(st = GetAll(in.force(), where + " force", &b->force)).ok()) return st;
  if (!(st = GetAll(in.torque(), where + " torque", &b->torque)).ok()) return st;
  if (!(st = GetAll(in.kinematic_v(), where + " kinematic_v", &b->kinematic_v)).ok()) return st;
  if (!(st = GetAll(in.kinematic_w(), where + " kinematic_w", &b->kinematic_w)).ok()) return st;
  b->q = Quat(q[0], q[1], q[2], q[3]);  // as stored: no normalisation, bit for bit
  b->rest_time = in.rest_time();
  b->sleep_island = in.sleep_island();
  b->collision_category = in.collision_category();
  b->collision_mask = in.collision_mask();
  b->collision_group = in.collision_group();
  if (b->sleep_island < 0 || (b->sleep_island != 0 && !b->IsDynamic())) {
    return Status::InvalidArgument("snapshot: " + where + " sleep_island must be 0, or > 0 on a dynamic body, got " +
                                   std::to_string(b->sleep_island));
  }
  return Status::Ok();
}

// Written only when the joint has settings other than none, so that a
// snapshot of a world without actuators keeps its bytes.
void SaveJointActuator(const JointActuator& a, proto::SnapshotJoint* joint) {
  const JointActuator none;
  if (a.torque == none.torque && a.target_position == none.target_position &&
      a.target_velocity == none.target_velocity && a.kp == none.kp && a.kd == none.kd &&
      a.effort_limit == none.effort_limit && a.velocity_limit == none.velocity_limit) {
    return;
  }
  proto::SnapshotJointActuator* out = joint->mutable_actuator();
  out->set_torque(a.torque);
  out->set_target_position(a.target_position);
  out->set_target_velocity(a.target_velocity);
  out->set_kp(a.kp);
  out->set_kd(a.kd);
  if (std::isfinite(a.effort_limit)) out->set_effort_limit(a.effort_limit);
  if (std::isfinite(a.velocity_limit)) out->set_velocity_limit(a.velocity_limit);
}

Status LoadJointActuator(const proto::SnapshotJoint& p, Joint* j) {
  j->actuator = JointActuator();
  if (!p.has_actuator()) return Status::Ok();
  if (!HasJointCoordinate(j->kind)) {
    return Status::InvalidArgument("snapshot: joint " + std::to_string(p.id()) + " is a " + JointKindName(j->kind) +
                                   " joint, which takes no actuator");
  }
  const proto::SnapshotJointActuator& in = p.actuator();
  JointActuator& a = j->actuator;
  a.torque = in.torque();
  a.target_position = in.target_position();
  a.target_velocity = in.target_velocity();
  a.kp = in.kp();
  a.kd = in.kd();
  if (in.has_effort_limit()) a.effort_limit = in.effort_limit();
  if (in.has_velocity_limit()) a.velocity_limit = in.velocity_limit();
  const Status st = CheckJointActuator(a);
  return st.ok() ? st : st.Prefixed("snapshot: joint " + std::to_string(p.id()) + ": ");
}

}  // namespace

void SaveJoint(const Joint& j, proto::SnapshotJoint* out) {
  out->set_id(j.id);
  out->set_kind(static_cast<int32_t>(j.kind));
  out->set_body_a(j.body_a);
  out->set_body_b(j.body_b);
  PutAll(j.anchor_a, out->mutable_anchor_a());
  PutAll(j.anchor_b, out->mutable_anchor_b());
  PutAll(j.axis_a, out->mutable_axis_a());
  PutAll(j.axis_b, out->mutable_axis_b());
  PutAll(Eigen::Vector4d(j.rest.w(), j.rest.x(), j.rest.y(), j.rest.z()), out->mutable_rest());
  out->set_length(j.length);
  out->set_limited(j.limited);
  out->set_lower(j.lower);
  out->set_upper(j.upper);
  // only when set, so that a snapshot of a world without them keeps its bytes
  if (j.damping != 0.0) out->set_damping(j.damping);
  if (j.friction != 0.0) out->set_friction(j.friction);
  if (j.collide_connected) out->set_collide_connected(true);
  SaveJointActuator(j.actuator, out);
  if (j.effort != 0.0) out->set_effort(j.effort);
  if (j.mimic.master != 0) {
    out->set_mimic_master(j.mimic.master);
    out->set_mimic_multiplier(j.mimic.multiplier);
    out->set_mimic_offset(j.mimic.offset);
  }
}

Status LoadJoint(const proto::SnapshotJoint& p, Joint* j) {
  if (p.kind() < 0 || p.kind() > static_cast<int32_t>(JointKind::kPrismatic)) {
    return Status::InvalidArgument("snapshot: joint " + std::to_string(p.id()) + " kind must be in [0, 4], got " +
                                   std::to_string(p.kind()));
  }
  j->id = p.id();
  j->kind = static_cast<JointKind>(p.kind());
  j->body_a = p.body_a();
  j->body_b = p.body_b();
  Eigen::Vector4d rest;
  Status st = GetAll(p.anchor_a(), "joint anchor_a", &j->anchor_a);
  if (st.ok()) st = GetAll(p.anchor_b(), "joint anchor_b", &j->anchor_b);
  if (st.ok()) st = GetAll(p.axis_a(), "joint axis_a", &j->axis_a);
  if (st.ok()) st = GetAll(p.axis_b(), "joint axis_b", &j->axis_b);
  if (st.ok()) st = GetAll(p.rest(), "joint rest", &rest);
  if (!st.ok()) return st;
  j->rest = Quat(rest[0], rest[1], rest[2], rest[3]);
  j->length = p.length();
  j->limited = p.limited();
  j->lower = p.lower();
  j->upper = p.upper();
  if (!std::isfinite(p.damping()) || p.damping() < 0.0 || !std::isfinite(p.friction()) || p.friction() < 0.0) {
    return Status::InvalidArgument("snapshot: joint " + std::to_string(p.id()) +
                                   " damping and friction must be finite and >= 0");
  }
  j->damping = p.damping();
  j->friction = p.friction();
  j->collide_connected = p.collide_connected();
  if (!std::isfinite(p.effort())) {
    return Status::InvalidArgument("snapshot: joint " + std::to_string(p.id()) + " effort must be finite");
  }
  j->effort = p.effort();
  // checked against the other joints by World::AssignJoints
  j->mimic = JointMimic{p.mimic_master(), p.mimic_multiplier(), p.mimic_offset()};
  return LoadJointActuator(p, j);
}

void SaveSnapshot(const World& world, const ContactMethod& method, proto::Snapshot* out) {
  out->Clear();
  out->set_format(1);
  out->set_step(world.step);
  out->set_time(world.time);
  out->set_dt(world.dt);
  PutAll(world.gravity, out->mutable_gravity());
  out->set_next_id(world.next_id);
  proto::SnapshotSleep* sleep = out->mutable_sleep();
  sleep->set_enabled(world.sleep.enabled);
  sleep->set_linear_speed(world.sleep.linear_speed);
  sleep->set_angular_speed(world.sleep.angular_speed);
  sleep->set_time_to_sleep(world.sleep.time_to_sleep);
  for (const RigidBody& b : world.bodies()) SaveBody(b, out->add_bodies());
  for (const TimedWrench& w : world.wrenches()) {
    proto::SnapshotWrench* pw = out->add_wrenches();
    pw->set_body(w.body);
    PutAll(w.force, pw->mutable_force());
    PutAll(w.torque, pw->mutable_torque());
    pw->set_remaining(w.remaining);
  }
  for (const Joint& j : world.joints()) SaveJoint(j, out->add_joints());
  out->set_next_joint_id(world.next_joint_id);
  SaveSensors(world.sensors, out);
  for (const ModelRecord& m : world.models) SaveModelRecord(m, out->add_models());
  out->set_next_model_id(world.next_model_id);
  out->set_contact_method(method.Name());
  for (const auto& [name, value] : method.Params()) {
    proto::Param* p = out->add_method_params();
    p->set_name(name);
    p->set_value(value);
  }
  out->set_method_state(method.SaveState());
  out->set_state_hash(HashWorldState(world));
}

Status LoadSnapshot(const proto::Snapshot& snap, World* world, std::shared_ptr<ContactMethod>* method) {
  if (snap.format() != 1) {
    return Status::InvalidArgument("snapshot: format must be 1, got " + std::to_string(snap.format()));
  }
  World w;
  w.step = snap.step();
  w.time = snap.time();
  w.dt = snap.dt();
  w.next_id = snap.next_id();
  Status st;
  if (snap.has_sleep() && !(st = LoadSleep(snap.sleep(), &w.sleep)).ok()) return st;
  st = GetAll(snap.gravity(), "gravity", &w.gravity);
  if (!st.ok()) return st;
  std::vector<RigidBody> bodies(snap.bodies_size());
  for (int i = 0; i < snap.bodies_size(); ++i) {
    if (!(st = LoadBody(snap.bodies(i), &bodies[i])).ok()) return st;
  }
  std::vector<TimedWrench> wrenches(snap.wrenches_size());
  for (int i = 0; i < snap.wrenches_size(); ++i) {
    const proto::SnapshotWrench& pw = snap.wrenches(i);
    wrenches[i].body = pw.body();
    wrenches[i].remaining = pw.remaining();
    if (!(st = GetAll(pw.force(), "wrench force", &wrenches[i].force)).ok()) return st;
    if (!(st = GetAll(pw.torque(), "wrench torque", &wrenches[i].torque)).ok()) return st;
  }
  for (const RigidBody& b : bodies) {
    if (b.asleep() && !w.sleep.enabled) {
      return Status::InvalidArgument("snapshot: body " + std::to_string(b.id) + " sleeps but sleep is off");
    }
  }
  if (!(st = w.Assign(std::move(bodies), std::move(wrenches), snap.next_id())).ok()) {
    return Status::InvalidArgument("snapshot: " + st.message());
  }
  std::vector<Joint> joints(snap.joints_size());
  for (int i = 0; i < snap.joints_size(); ++i) {
    if (!(st = LoadJoint(snap.joints(i), &joints[i])).ok()) return st;
  }
  if (!(st = w.AssignJoints(std::move(joints), snap.next_joint_id())).ok()) {
    return Status::InvalidArgument("snapshot: " + st.message());
  }
  if (!(st = LoadSensors(snap, &w)).ok()) return st;
  for (const proto::ModelRecord& pm : snap.models()) {
    w.models.emplace_back();
    if (!(st = LoadModelRecord(pm, &w.models.back())).ok()) return Status::InvalidArgument("snapshot: " + st.message());
  }
  w.next_model_id = snap.next_model_id();
  if (snap.has_state_hash() && HashWorldState(w) != snap.state_hash()) {
    return Status::InvalidArgument("snapshot: the bodies do not match the stored state hash");
  }
  std::unique_ptr<ContactMethod> m;
  if (!(st = CreateContactMethod(snap.contact_method(), &m)).ok()) return st;
  ParamMap params;
  for (const proto::Param& p : snap.method_params()) params[p.name()] = p.value();
  if (!(st = m->SetParams(params)).ok()) return st;
  if (!(st = m->LoadState(snap.method_state())).ok()) return st;
  *world = std::move(w);
  *method = std::move(m);
  return Status::Ok();
}

Status WriteSnapshotFile(const std::string& path, const proto::Snapshot& snap, bool sync) {
  const std::string tmp = path + ".tmp";
  const std::string bytes = snap.SerializeAsString();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return Status::FailedPrecondition("cannot write snapshot file " + tmp);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  const bool ok = done == bytes.size() && (!sync || ::fsync(fd) == 0);
  ::close(fd);
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    ::unlink(tmp.c_str());
    return Status::FailedPrecondition("cannot write snapshot file " + path);
  }
  if (sync) {
    // the rename is durable only once the folder is
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash == 0 ? 1 : slash);
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) {
      ::fsync(dfd);
      ::close(dfd);
    }
  }
  return Status::Ok();
}

Status ReadSnapshotFile(const std::string& path, proto::Snapshot* snap) {
  std::string bytes;
  const Status st = ReadFileBounded(path, &bytes);
  if (!st.ok()) return st.Prefixed("snapshot file ");
  if (!snap->ParseFromString(bytes)) return Status::InvalidArgument(path + ": not a snapshot (binary protobuf)");
  return Status::Ok();
}

}  // namespace contactsim
