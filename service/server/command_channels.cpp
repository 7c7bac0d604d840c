#include "service/server/command_channels.h"

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/model_cmd_t.hpp>
#include <contactsim/protocol.hpp>
#include <contactsim/ray_cast_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/sensor_cmd_t.hpp>
#include <contactsim/wire_check.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string_view>
#include <vector>

#include "service/model/mesh_reader.h"
#include "service/model/model_paths.h"
#include "service/physics/body_settings.h"
#include "service/scene/height_map_file.h"
#include "service/server/command_decoder.h"
#include "service/server/journal.h"

namespace contactsim {
namespace {

// A MESH given by path: the file read (service/model/mesh_reader.h) into
// the command's points and indices, the path cleared, and that resolved
// form kept as the payload the journal records, so that a replay or a
// recovery builds the same mesh whatever happens to the file.
Status ResolveMeshPath(const body_cmd_t& m, const DecodeContext& context, body_cmd_t* kept, Command* cmd) {
  if (m.num_points != 0 || m.num_mesh_indices != 0) {
    return Status::InvalidArgument("a MESH gives mesh_path or points and mesh_indices, not both");
  }
  if (m.mesh_path.size() > 4096) {
    return Status::InvalidArgument("mesh_path of " + std::to_string(m.mesh_path.size()) + " bytes is longer than 4096");
  }
  std::string path;
  Status st = model::ResolveModelFile(m.mesh_path, context.model_paths, &path);
  std::vector<Vec3> vertices;
  std::vector<int> indices;
  if (st.ok()) st = model::ReadMeshTriangles(path, Vec3::Ones(), model::ReadLimits(), &vertices, &indices);
  if (!st.ok()) return st;
  *kept = m;
  kept->mesh_path.clear();
  kept->num_points = static_cast<int32_t>(vertices.size());
  kept->points.clear();
  for (const Vec3& v : vertices) kept->points.push_back({v.x(), v.y(), v.z()});
  kept->num_mesh_indices = static_cast<int32_t>(indices.size());
  kept->mesh_indices.assign(indices.begin(), indices.end());
  cmd->payload.resize(kept->getEncodedSize());
  kept->encode(cmd->payload.data(), 0, static_cast<int>(cmd->payload.size()));
  return Status::Ok();
}

// A HEIGHTFIELD given by path: the height map read
// (service/scene/height_map_file.h) into the command's rows, cols and
// heights, the path, scale and offset cleared, and that resolved form kept
// as the journal's payload, as a mesh's is above.
Status ResolveHeightPath(const body_cmd_t& m, const DecodeContext& context, body_cmd_t* kept, Command* cmd) {
  if (m.num_heights != 0) return Status::InvalidArgument("a HEIGHTFIELD gives height_path or heights, not both");
  if (m.height_path.size() > 4096) {
    return Status::InvalidArgument("height_path of " + std::to_string(m.height_path.size()) +
                                   " bytes is longer than 4096");
  }
  std::string path;
  Status st = model::ResolveModelFile(m.height_path, context.model_paths, &path);
  HeightMap map;
  if (st.ok()) {
    st = ReadHeightMap(path, m.height_rows, m.height_cols, m.height_scale == 0.0 ? 1.0 : m.height_scale,
                       m.height_offset, &map);
  }
  if (!st.ok()) return st;
  // the command is journaled with the heights: it must fit one record
  const uint64_t bytes = m.getEncodedSize() + sizeof(double) * map.heights.size();
  if (bytes > kMaxJournalPayload) {
    return Status::ResourceExhausted("height map '" + path + "' of " + std::to_string(map.rows) + " x " +
                                     std::to_string(map.cols) + " samples makes a command of " +
                                     std::to_string(bytes) + " bytes, over the journal's record limit of " +
                                     std::to_string(kMaxJournalPayload) + " (about 8.3 million samples)");
  }
  *kept = m;
  kept->height_path.clear();
  kept->height_scale = kept->height_offset = 0.0;
  kept->height_rows = map.rows;
  kept->height_cols = map.cols;
  kept->num_heights = static_cast<int32_t>(map.heights.size());
  kept->heights = std::move(map.heights);
  cmd->payload.resize(kept->getEncodedSize());
  kept->encode(cmd->payload.data(), 0, static_cast<int>(cmd->payload.size()));
  return Status::Ok();
}

Status CheckBody(const body_cmd_t& m, const DecodeContext& context, Command* cmd) {
  if (m.shape == body_cmd_t::HEIGHTFIELD && !m.height_path.empty()) {
    body_cmd_t kept;
    Status st = ResolveHeightPath(m, context, &kept, cmd);
    return st.ok() ? DecodeBodyCommand(kept, context.default_material, cmd) : st;
  }
  if (m.shape == body_cmd_t::MESH) {
    // a mesh's points are its vertices, bounded by the message size and the mesh's triangle limit
    if (m.mesh_path.empty()) return DecodeBodyCommand(m, context.default_material, cmd);
    body_cmd_t kept;
    Status st = ResolveMeshPath(m, context, &kept, cmd);
    return st.ok() ? DecodeBodyCommand(kept, context.default_material, cmd) : st;
  }
  if (m.num_points > context.limits.max_convex_points) {
    return Status::ResourceExhausted("num_points " + std::to_string(m.num_points) + " exceeds max_convex_points = " +
                                     std::to_string(context.limits.max_convex_points));
  }
  // a compound's parts share the bound of one hull's points
  if (m.num_part_points > context.limits.max_convex_points) {
    return Status::ResourceExhausted("num_part_points " + std::to_string(m.num_part_points) +
                                     " exceeds max_convex_points = " + std::to_string(context.limits.max_convex_points));
  }
  if (m.num_parts > kMaxShapeParts) {
    return Status::ResourceExhausted("num_parts " + std::to_string(m.num_parts) + " exceeds " +
                                     std::to_string(kMaxShapeParts));
  }
  return DecodeBodyCommand(m, context.default_material, cmd);
}

Status CheckScene(const scene_cmd_t& m, const DecodeContext&, Command* cmd) { return DecodeSceneCommand(m, cmd); }
Status CheckJoint(const joint_cmd_t& m, const DecodeContext&, Command* cmd) { return DecodeJointCommand(m, cmd); }
Status CheckModel(const model_cmd_t& m, const DecodeContext& context, Command* cmd) {
  return DecodeModelCommand(m, context, cmd);
}
Status CheckActuator(const actuator_cmd_t& m, const DecodeContext&, Command* cmd) {
  return DecodeActuatorCommand(m, cmd);
}
Status CheckInput(const input_t& m, const DecodeContext&, Command* cmd) { return DecodeInput(m, cmd); }
Status CheckSensor(const sensor_cmd_t& m, const DecodeContext& context, Command* cmd) {
  return DecodeSensorCommand(m, context.limits.max_rays_per_sensor, cmd);
}
Status CheckRayCast(const ray_cast_t& m, const DecodeContext& context, Command* cmd) {
  return DecodeRayCast(m, context.limits.max_rays_per_cast, cmd);
}

// The total decoder of one channel: size limit, bounds check of the
// encoding, the generated decode, then the command's own checks, with
// anything thrown on the way (an allocation failure) turned into a status.
template <typename Msg, int DecodeLimits::*kMaxBytes,
          Status (*kCheck)(const Msg&, const DecodeContext&, Command*)>
Status Decode(const void* data, int size, const DecodeContext& context, Command* cmd) {
  const std::string what = std::string(Msg::getTypeName()) + " payload of " + std::to_string(size) + " bytes";
  if (size > context.limits.*kMaxBytes) {
    return Status::ResourceExhausted(what + " exceeds the channel's limit of " +
                                     std::to_string(context.limits.*kMaxBytes) + " bytes");
  }
  std::string why;
  if (data == nullptr || !wire::Check<Msg>(data, size, &why)) return Status::DecodeError("undecodable " + what + ": " + why);
  try {
    Msg msg;
    if (msg.decode(data, 0, size) != size) return Status::DecodeError("undecodable " + what);
    cmd->client_id = msg.client_id;
    cmd->request_id = msg.request_id;
    Status st = context.admit ? context.admit(msg.client_id) : Status::Ok();
    if (st.ok()) st = kCheck(msg, context, cmd);
    // a decoder may store the command in another form (a model LOAD as read)
    if (st.ok() && cmd->payload.empty()) cmd->payload.assign(static_cast<const char*>(data), size);
    return st;
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted(what + ": out of memory while decoding");
  } catch (const std::exception& e) {
    return Status::DecodeError(what + ": " + e.what());
  }
}

// The row of the protocol's incoming channel `name` (lcmtypes/protocol.toml):
// its suffix, type and whether it is replied come from the protocol, the
// decoder and journal record from here. A decoder of another type than the
// protocol's is a programmer's error, caught when the table is built.
template <typename Msg, int DecodeLimits::*kMaxBytes,
          Status (*kCheck)(const Msg&, const DecodeContext&, Command*)>
CommandChannel Row(const char* name, RecordKind record) {
  const protocol::ChannelSpec* spec = protocol::FindChannel(name);
  if (spec == nullptr || !spec->incoming || std::string_view(spec->type_name) != Msg::getTypeName()) {
    std::fprintf(stderr, "command channel %s: lcmtypes/protocol.toml has no incoming channel of type %s\n", name,
                 Msg::getTypeName());
    std::abort();
  }
  return {spec->name, spec->type_name, record, spec->replied, &Decode<Msg, kMaxBytes, kCheck>};
}

}  // namespace

const std::vector<CommandChannel>& CommandChannels() {
  static const std::vector<CommandChannel> kChannels = {
      Row<body_cmd_t, &DecodeLimits::max_body_cmd_bytes, CheckBody>(protocol::kBodyCmd, RecordKind::kBodyCommand),
      Row<scene_cmd_t, &DecodeLimits::max_scene_cmd_bytes, CheckScene>(protocol::kSceneCmd,
                                                                       RecordKind::kSceneCommand),
      Row<joint_cmd_t, &DecodeLimits::max_joint_cmd_bytes, CheckJoint>(protocol::kJointCmd,
                                                                       RecordKind::kJointCommand),
      Row<model_cmd_t, &DecodeLimits::max_model_cmd_bytes, CheckModel>(protocol::kModelCmd,
                                                                       RecordKind::kModelCommand),
      Row<input_t, &DecodeLimits::max_input_bytes, CheckInput>(protocol::kInput, RecordKind::kInput),
      Row<sensor_cmd_t, &DecodeLimits::max_sensor_cmd_bytes, CheckSensor>(protocol::kSensorCmd,
                                                                          RecordKind::kSensorCommand),
      Row<ray_cast_t, &DecodeLimits::max_ray_cast_bytes, CheckRayCast>(protocol::kRayCast,
                                                                       RecordKind::kNotJournaled),
      Row<actuator_cmd_t, &DecodeLimits::max_actuator_cmd_bytes, CheckActuator>(protocol::kActuatorCmd,
                                                                                 RecordKind::kActuatorCommand),
  };
  return kChannels;
}

const CommandChannel* ChannelOfRecord(RecordKind kind) {
  for (const CommandChannel& c : CommandChannels()) {
    if (c.record == kind) return &c;
  }
  return nullptr;
}

const CommandChannel* ChannelOfSuffix(const std::string& suffix) {
  for (const CommandChannel& c : CommandChannels()) {
    if (suffix == c.suffix) return &c;
  }
  return nullptr;
}

}  // namespace contactsim
