#include "service/server/command_decoder.h"

#include <algorithm>
#include <cctype>

#include "service/collision/height_field.h"
#include "service/collision/triangle_mesh.h"
#include "service/contact/contact_method_registry.h"
#include "service/physics/body_settings.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

Vec3 V3(const double v[3]) { return Vec3(v[0], v[1], v[2]); }
Vec3 V3(const std::vector<double>& v) { return Vec3(v[0], v[1], v[2]); }  // a row of 3 (wire-checked)

// The wire's shape code; false for an unknown one.
bool ShapeOfCode(int8_t code, ShapeType* type) {
  switch (code) {
    case body_cmd_t::SPHERE: *type = ShapeType::kSphere; return true;
    case body_cmd_t::BOX: *type = ShapeType::kBox; return true;
    case body_cmd_t::PLANE: *type = ShapeType::kPlane; return true;
    case body_cmd_t::CAPSULE: *type = ShapeType::kCapsule; return true;
    case body_cmd_t::CONVEX: *type = ShapeType::kConvex; return true;
    case body_cmd_t::COMPOUND: *type = ShapeType::kCompound; return true;
    case body_cmd_t::MESH: *type = ShapeType::kMesh; return true;
    case body_cmd_t::HEIGHTFIELD: *type = ShapeType::kHeightfield; return true;
    default: return false;
  }
}

// The parts of a COMPOUND: every count consistent, then each part's fields
// as CreateBody checks them (a plane or compound part is refused there).
Status DecodeParts(const body_cmd_t& m, BodySettings* s) {
  const size_t n = static_cast<size_t>(std::max(m.num_parts, 0));
  if (m.num_parts < 0 || m.part_shape.size() != n) {
    return Status::InvalidArgument("num_parts must equal the number of parts, got " + std::to_string(m.num_parts));
  }
  if (m.num_parts > 0 && m.shape != body_cmd_t::COMPOUND) {
    return Status::InvalidArgument("num_parts is for shape COMPOUND=6, got " + std::to_string(m.num_parts) +
                                   " part(s) with shape " + std::to_string(m.shape));
  }
  int64_t rows = 0;
  for (size_t k = 0; k < n; ++k) {
    if (m.part_num_points[k] < 0) {
      return Status::InvalidArgument("part_num_points[" + std::to_string(k) + "] must be >= 0, got " +
                                     std::to_string(m.part_num_points[k]));
    }
    rows += m.part_num_points[k];
  }
  if (m.num_part_points < 0 || rows != m.num_part_points) {
    return Status::InvalidArgument("num_part_points must be the sum of part_num_points (" + std::to_string(rows) +
                                   "), got " + std::to_string(m.num_part_points));
  }
  size_t row = 0;
  for (size_t k = 0; k < n; ++k) {
    ShapePart p;
    if (!ShapeOfCode(m.part_shape[k], &p.type)) {
      return Status::InvalidArgument("part_shape[" + std::to_string(k) +
                                     "] must be SPHERE=1, BOX=2, CAPSULE=4 or CONVEX=5, got " +
                                     std::to_string(m.part_shape[k]));
    }
    p.radius = m.part_radius[k];
    p.half_extents = V3(m.part_half_extents[k]);
    p.half_length = m.part_half_length[k];
    for (int i = 0; i < m.part_num_points[k]; ++i, ++row) p.points.push_back(V3(m.part_points[row]));
    p.position = V3(m.part_position[k]);
    const std::vector<double>& q = m.part_orientation[k];
    p.orientation = Quat(q[0], q[1], q[2], q[3]);  // (w, x, y, z); CreateBody checks and normalises it
    s->parts.push_back(std::move(p));
  }
  return Status::Ok();
}

// A MESH's or HEIGHTFIELD's surface, built and checked by the collision
// layer (a mesh given by path was read into points and indices before,
// CheckBody); the fields of the other one must be empty.
Status DecodeSurface(const body_cmd_t& m, BodySettings* s, std::string* note) {
  const bool mesh = m.shape == body_cmd_t::MESH, field = m.shape == body_cmd_t::HEIGHTFIELD;
  if (!mesh && (m.num_mesh_indices != 0 || !m.mesh_path.empty())) {
    return Status::InvalidArgument("mesh_indices and mesh_path are for shape MESH=7, got shape " +
                                   std::to_string(m.shape));
  }
  if (!field && (m.num_heights != 0 || !m.height_path.empty())) {
    return Status::InvalidArgument("heights and height_path are for shape HEIGHTFIELD=8, got shape " +
                                   std::to_string(m.shape));
  }
  // a height map's scale and offset are applied when it is read (command_channels.cpp)
  if (m.height_scale != 0.0 || m.height_offset != 0.0) {
    return Status::InvalidArgument("height_scale and height_offset are for a height_path, got " +
                                   std::to_string(m.height_scale) + " and " + std::to_string(m.height_offset));
  }
  if (mesh) {
    if (m.num_mesh_indices < 0 || static_cast<size_t>(m.num_mesh_indices) != m.mesh_indices.size()) {
      return Status::InvalidArgument("num_mesh_indices must equal the number of indices, got " +
                                     std::to_string(m.num_mesh_indices));
    }
    std::vector<Vec3> vertices;
    for (const auto& p : m.points) vertices.emplace_back(p[0], p[1], p[2]);
    const std::vector<int> indices(m.mesh_indices.begin(), m.mesh_indices.end());
    MeshBuildReport report;
    Status st = BuildTriangleMesh(vertices, indices, m.mesh_scale == 0.0 ? 1.0 : m.mesh_scale, &s->mesh, &report);
    if (!st.ok()) return st;
    if (report.dropped_degenerate > 0) {
      *note = std::to_string(report.dropped_degenerate) + " triangle(s) of zero area dropped";
    }
    return Status::Ok();
  }
  if (field) {
    if (m.num_heights < 0 || static_cast<size_t>(m.num_heights) != m.heights.size()) {
      return Status::InvalidArgument("num_heights must equal the number of heights, got " +
                                     std::to_string(m.num_heights));
    }
    return BuildHeightField(m.height_rows, m.height_cols, m.heights, m.height_spacing[0], m.height_spacing[1],
                            &s->heightfield);
  }
  return Status::Ok();
}

// The explicit mass properties: the inertia's six unique entries.
void DecodeMassProperties(const body_cmd_t& m, BodySettings* s) {
  if (m.has_center_of_mass) s->center_of_mass = V3(m.center_of_mass);
  if (m.has_inertia) {
    const double* i = m.inertia;  // ixx, iyy, izz, ixy, ixz, iyz
    Mat3 I;
    I << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
    s->inertia = I;
  }
}

Status DecodeAdd(const body_cmd_t& m, const Material& default_material, Command* cmd) {
  BodySettings s;
  s.name = m.name;
  if (!ShapeOfCode(m.shape, &s.shape)) {
    return Status::InvalidArgument("shape must be one of SPHERE=1, BOX=2, PLANE=3, CAPSULE=4, CONVEX=5, COMPOUND=6, "
                                   "MESH=7, HEIGHTFIELD=8, got " + std::to_string(m.shape));
  }
  Status parts = DecodeParts(m, &s);
  if (!parts.ok()) return parts;
  Status surface = DecodeSurface(m, &s, &cmd->reply_note);
  if (!surface.ok()) return surface;
  DecodeMassProperties(m, &s);
  s.radius = m.radius;
  s.half_extents = V3(m.half_extents);
  s.half_length = m.half_length;
  s.plane_normal = V3(m.plane_normal);
  s.plane_offset = m.plane_offset;
  if (m.num_points < 0 || static_cast<size_t>(m.num_points) != m.points.size()) {
    return Status::InvalidArgument("num_points must equal the number of points, got " + std::to_string(m.num_points));
  }
  // a mesh's points are its vertices (DecodeSurface)
  if (m.shape != body_cmd_t::MESH) {
    for (const auto& p : m.points) s.points.emplace_back(p[0], p[1], p[2]);
  }
  // 0 means "not given" for mass and density; anything else is checked
  if (m.mass != 0.0) s.mass = m.mass;
  if (m.density != 0.0) s.density = m.density;
  s.fixed = m.fixed;
  s.kinematic = m.kinematic;
  s.position = V3(m.position);
  s.orientation = Eigen::Vector4d(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
  s.linear_velocity = V3(m.linear_velocity);
  s.angular_velocity = V3(m.angular_velocity);
  if (m.has_restitution) s.restitution = m.restitution;
  if (m.has_friction) s.friction = m.friction;
  if (m.has_filter) {
    s.collision_category = static_cast<uint32_t>(m.collision_category);  // the wire's bit pattern
    s.collision_mask = static_cast<uint32_t>(m.collision_mask);
    s.collision_group = m.collision_group;
  }
  cmd->kind = Command::Kind::kAddBody;
  return CreateBody(s, default_material, &cmd->new_body);
}

// A slot name, or a path, exactly one of them.
Status DecodeSnapshotTarget(const scene_cmd_t& m, Command* cmd) {
  if (m.name.empty() == m.path.empty()) {
    return Status::InvalidArgument("give exactly one of name or path, got name \"" + m.name + "\", path \"" +
                                   m.path + "\"");
  }
  const bool name_ok = m.name.size() <= 64 && std::all_of(m.name.begin(), m.name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
  });
  if (!name_ok) {
    return Status::InvalidArgument("name must be 1 to 64 of [A-Za-z0-9_.-], got \"" + m.name + "\"");
  }
  cmd->snapshot_name = m.name;
  cmd->snapshot_path = m.path;
  return Status::Ok();
}

}  // namespace

Status DecodeBodyCommand(const body_cmd_t& m, const Material& default_material, Command* cmd) {
  cmd->client_id = m.client_id;
  cmd->request_id = m.request_id;
  cmd->body_id = m.body_id;
  Status st;
  switch (m.op) {
    case body_cmd_t::ADD: return DecodeAdd(m, default_material, cmd);
    case body_cmd_t::REMOVE: cmd->kind = Command::Kind::kRemoveBody; return Status::Ok();
    case body_cmd_t::SET_POSE:
      cmd->kind = Command::Kind::kSetPose;
      cmd->position = V3(m.position);
      if (!(st = CheckFinite("position", cmd->position)).ok()) return st;
      return MakeOrientation("orientation",
                             Eigen::Vector4d(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]),
                             false, &cmd->orientation);
    case body_cmd_t::SET_VELOCITY:
      cmd->kind = Command::Kind::kSetVelocity;
      cmd->linear = V3(m.linear_velocity);
      cmd->angular = V3(m.angular_velocity);
      if (!(st = CheckFinite("linear_velocity", cmd->linear)).ok()) return st;
      return CheckFinite("angular_velocity", cmd->angular);
    case body_cmd_t::APPLY_FORCE:
      cmd->kind = Command::Kind::kApplyForce;
      cmd->linear = V3(m.force);
      cmd->angular = V3(m.torque);
      cmd->duration = m.duration;
      if (!(st = CheckFinite("force", cmd->linear)).ok()) return st;
      if (!(st = CheckFinite("torque", cmd->angular)).ok()) return st;
      return CheckNonNegative("duration", m.duration);
    case body_cmd_t::APPLY_IMPULSE:
      cmd->kind = Command::Kind::kApplyImpulse;
      cmd->linear = V3(m.impulse);
      if (!(st = CheckFinite("impulse", cmd->linear)).ok()) return st;
      if (m.has_point) {
        cmd->point = V3(m.point);
        return CheckFinite("point", *cmd->point);
      }
      return Status::Ok();
    case body_cmd_t::SET_MASS:
      cmd->kind = Command::Kind::kSetMass;
      if ((m.mass != 0.0) == (m.density != 0.0)) {
        return Status::InvalidArgument("give exactly one of mass or density, got mass " + FormatValue(m.mass) +
                                       ", density " + FormatValue(m.density));
      }
      if (m.mass != 0.0) {
        cmd->mass = m.mass;
        return CheckPositive("mass", m.mass);
      }
      cmd->density = m.density;
      return CheckPositive("density", m.density);
    case body_cmd_t::SET_MATERIAL:
      cmd->kind = Command::Kind::kSetMaterial;
      if (m.has_restitution) cmd->restitution = m.restitution;
      if (m.has_friction) cmd->friction = m.friction;
      return CheckMaterial(cmd->restitution, cmd->friction);
    case body_cmd_t::SET_FILTER:  // every bit pattern is a filter
      cmd->kind = Command::Kind::kSetFilter;
      cmd->collision_category = static_cast<uint32_t>(m.collision_category);
      cmd->collision_mask = static_cast<uint32_t>(m.collision_mask);
      cmd->collision_group = m.collision_group;
      return Status::Ok();
    default: break;
  }
  return Status::InvalidArgument("op must be one of ADD=1 .. SET_FILTER=9, got " + std::to_string(m.op));
}

Status DecodeSceneCommand(const scene_cmd_t& m, Command* cmd) {
  cmd->client_id = m.client_id;
  cmd->request_id = m.request_id;
  Status st;
  switch (m.op) {
    case scene_cmd_t::RESET: cmd->kind = Command::Kind::kReset; return Status::Ok();
    case scene_cmd_t::LOAD_SCENE: {
      cmd->kind = Command::Kind::kLoadScene;
      cmd->scene_path = m.path;
      if (m.path.empty()) return Status::InvalidArgument("path must name a scene file on the server's host, got \"\"");
      auto scene = std::make_shared<SceneSpec>();
      if (!(st = LoadSceneFile(m.path, scene.get())).ok()) return st;
      // build once here so that a bad body is reported now, not mid-run
      World probe;
      if (!(st = BuildWorld(*scene, &probe)).ok()) return st;
      if (!scene->contact_method.empty() &&
          !(st = MakeContactMethod(scene->contact_method, scene->method_params, &cmd->method)).ok()) {
        return Status::InvalidArgument(m.path + ": " + st.message());
      }
      cmd->scene = std::move(scene);
      return Status::Ok();
    }
    case scene_cmd_t::SET_GRAVITY:
      cmd->kind = Command::Kind::kSetGravity;
      cmd->gravity = V3(m.gravity);
      return CheckFinite("gravity", cmd->gravity);
    case scene_cmd_t::SET_TIMESTEP:
      cmd->kind = Command::Kind::kSetTimestep;
      cmd->dt = m.dt;
      return CheckInRange("dt", m.dt, 1e-6, 0.1);
    case scene_cmd_t::SET_METHOD: {
      cmd->kind = Command::Kind::kSetMethod;
      if (m.num_params < 0 || static_cast<size_t>(m.num_params) != m.param_names.size() ||
          m.param_names.size() != m.param_values.size()) {
        return Status::InvalidArgument("num_params must equal the number of parameter names and values, got " +
                                       std::to_string(m.num_params));
      }
      ParamMap params;
      for (size_t i = 0; i < m.param_names.size(); ++i) params[m.param_names[i]] = m.param_values[i];
      return MakeContactMethod(m.method, params, &cmd->method);
    }
    case scene_cmd_t::PAUSE: cmd->kind = Command::Kind::kPause; return Status::Ok();
    case scene_cmd_t::RESUME: cmd->kind = Command::Kind::kResume; return Status::Ok();
    case scene_cmd_t::STEP:
      cmd->kind = Command::Kind::kStep;
      cmd->steps = m.steps;
      if (m.steps < 1 || m.steps > 100000000) {
        return Status::InvalidArgument("steps must be in [1, 100000000], got " + std::to_string(m.steps));
      }
      return Status::Ok();
    case scene_cmd_t::SET_MODE:
      cmd->kind = Command::Kind::kSetMode;
      if (m.mode != scene_cmd_t::REALTIME && m.mode != scene_cmd_t::FREE_RUN && m.mode != scene_cmd_t::LOCKSTEP) {
        return Status::InvalidArgument("mode must be REALTIME=1, FREE_RUN=2 or LOCKSTEP=3, got " +
                                       std::to_string(m.mode));
      }
      cmd->mode = static_cast<RunMode>(m.mode);
      cmd->real_time_factor = m.real_time_factor == 0.0 ? 1.0 : m.real_time_factor;
      return CheckInRange("real_time_factor", cmd->real_time_factor, 1e-3, 1e3);
    case scene_cmd_t::SNAPSHOT:
      cmd->kind = Command::Kind::kSnapshot;
      return DecodeSnapshotTarget(m, cmd);
    case scene_cmd_t::RESTORE:
      cmd->kind = Command::Kind::kRestore;
      return DecodeSnapshotTarget(m, cmd);
    case scene_cmd_t::REWIND:
      cmd->kind = Command::Kind::kRewind;
      cmd->target_step = m.target_step;
      if (m.target_step < 0) {
        return Status::InvalidArgument("target_step must be >= 0, got " + std::to_string(m.target_step));
      }
      return Status::Ok();
    case scene_cmd_t::REGISTER_CONTROLLER:
      cmd->kind = Command::Kind::kRegisterController;
      if (m.late_policy < scene_cmd_t::LATE_DEFAULT || m.late_policy > scene_cmd_t::LATE_DROP) {
        return Status::InvalidArgument("late_policy must be one of DEFAULT=0, WAIT=1, REUSE=2, DROP=3, got " +
                                       std::to_string(m.late_policy));
      }
      cmd->late_default = m.late_policy == scene_cmd_t::LATE_DEFAULT;
      if (!cmd->late_default) cmd->late_policy = static_cast<LatePolicy>(m.late_policy);
      cmd->late_timeout = m.late_timeout;
      if (m.late_timeout == 0.0) return Status::Ok();
      return CheckInRange("late_timeout", m.late_timeout, 1e-4, 3600.0);
    case scene_cmd_t::RELEASE_CONTROLLER:
      cmd->kind = Command::Kind::kReleaseController;
      return Status::Ok();
    default: break;
  }
  return Status::InvalidArgument("op must be one of RESET=1 .. RELEASE_CONTROLLER=14, got " + std::to_string(m.op));
}

Status DecodeInput(const input_t& m, Command* cmd) {
  cmd->kind = Command::Kind::kInput;
  cmd->client_id = m.client_id;
  cmd->request_id = m.request_id;
  ControllerInput& in = cmd->input;
  in.controller = m.client_id;
  in.request_id = m.request_id;
  in.step = m.step;
  const size_t n = static_cast<size_t>(std::max(0, m.num_bodies));
  if (m.num_bodies < 0 || m.body_ids.size() != n || m.forces.size() != n || m.torques.size() != n) {
    return Status::InvalidArgument("num_bodies must equal the number of body ids, forces and torques, got " +
                                   std::to_string(m.num_bodies));
  }
  Status st;
  for (size_t i = 0; i < n; ++i) {
    BodyInput b;
    b.body = m.body_ids[i];
    if (m.forces[i].size() != 3 || m.torques[i].size() != 3) {
      return Status::InvalidArgument("forces and torques need 3 numbers each");
    }
    b.force = V3(m.forces[i].data());
    b.torque = V3(m.torques[i].data());
    const std::string at = "[" + std::to_string(i) + "]";
    if (!(st = CheckFinite("forces" + at, b.force)).ok()) return st;
    if (!(st = CheckFinite("torques" + at, b.torque)).ok()) return st;
    in.bodies.push_back(b);
  }
  if (!(st = DecodeActuatorUpdate(m.joints, &in.joints)).ok()) return st;
  if (!in.joints.empty() && in.joints.fields == 0) {
    return Status::InvalidArgument("joints.fields names no field for " + std::to_string(in.joints.values.size()) +
                                   " joints");
  }
  return Status::Ok();
}

Status DecodeActuatorCommand(const actuator_cmd_t& m, Command* cmd) {
  cmd->client_id = m.client_id;
  cmd->request_id = m.request_id;
  if (m.op == actuator_cmd_t::STATE) {
    cmd->kind = Command::Kind::kJointStateQuery;
    return Status::Ok();
  }
  if (m.op != actuator_cmd_t::SET && m.op != actuator_cmd_t::CLEAR) {
    return Status::InvalidArgument("op must be SET=1, CLEAR=2 or STATE=3, got " + std::to_string(m.op));
  }
  cmd->kind = m.op == actuator_cmd_t::SET ? Command::Kind::kSetActuators : Command::Kind::kClearActuators;
  const Status st = DecodeActuatorUpdate(m.joints, &cmd->actuators);
  if (!st.ok()) return st;
  if (cmd->actuators.empty() && cmd->actuators.model == 0) {
    return Status::InvalidArgument("names no joint: give joints.joint_ids, or a joints.model_id");
  }
  if (m.op == actuator_cmd_t::SET && (cmd->actuators.fields == 0 || cmd->actuators.empty())) {
    return Status::InvalidArgument("SET: joints.fields names no field, or num_joints is 0");
  }
  return Status::Ok();
}

Status DecodeJointCommand(const joint_cmd_t& m, Command* cmd) {
  cmd->client_id = m.client_id;
  cmd->request_id = m.request_id;
  if (m.op == joint_cmd_t::REMOVE) {
    cmd->kind = Command::Kind::kRemoveJoint;
    cmd->joint_id = m.joint_id;
    return Status::Ok();
  }
  if (m.op != joint_cmd_t::ADD) {
    return Status::InvalidArgument("op must be ADD=1 or REMOVE=2, got " + std::to_string(m.op));
  }
  cmd->kind = Command::Kind::kAddJoint;
  JointSettings& s = cmd->joint;
  switch (m.kind) {
    case joint_cmd_t::DISTANCE: s.kind = JointKind::kDistance; break;
    case joint_cmd_t::BALL: s.kind = JointKind::kBall; break;
    case joint_cmd_t::HINGE: s.kind = JointKind::kHinge; break;
    case joint_cmd_t::FIXED: s.kind = JointKind::kFixed; break;
    case joint_cmd_t::PRISMATIC: s.kind = JointKind::kPrismatic; break;
    default:
      return Status::InvalidArgument("kind must be one of DISTANCE=1, BALL=2, HINGE=3, FIXED=4, PRISMATIC=5, got " +
                                     std::to_string(m.kind));
  }
  s.body_a = m.body_a;
  s.body_b = m.body_b;
  s.anchor = V3(m.anchor);
  if (m.has_axis) s.axis = V3(m.axis);
  if (m.has_length) s.length = m.length;
  if (m.has_limits) s.limits = std::make_pair(m.lower, m.upper);
  if (m.has_damping) s.damping = m.damping;
  if (m.has_friction) s.friction = m.friction;
  s.collide_connected = m.collide_connected;
  return CheckJointSettings(s);
}

}  // namespace contactsim
