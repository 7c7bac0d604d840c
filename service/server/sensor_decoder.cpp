// The decoders of the sensor and ray-cast channels (command_decoder.h).
#include <string>

#include "service/server/command_decoder.h"

namespace contactsim {
namespace {

Vec3 Read3(const double v[3]) { return Vec3(v[0], v[1], v[2]); }

}  // namespace

Status DecodeSensorCommand(const sensor_cmd_t& m, int max_rays, Command* cmd) {
  Status st = CheckSensorName(m.name);
  if (!st.ok()) return st;
  cmd->sensor_name = m.name;
  cmd->body_id = m.body_id;
  switch (m.op) {
    case sensor_cmd_t::ADD_RANGE: {
      cmd->kind = Command::Kind::kAddRangeSensor;
      RangeSensor& s = cmd->range_sensor;
      s.name = m.name;
      s.body = m.body_id;
      s.origin = Read3(m.origin);
      s.max_distance = m.max_distance;
      s.directions.reserve(m.directions.size());
      for (const auto& d : m.directions) s.directions.push_back(Read3(d.data()));
      if (m.num_rays > max_rays) {
        return Status::ResourceExhausted("range sensor of " + std::to_string(m.num_rays) +
                                         " rays exceeds max_rays_per_sensor = " + std::to_string(max_rays));
      }
      st = CheckRangeSensor(max_rays, s);
      if (!st.ok()) return st;
      NormaliseDirections(&s);
      return Status::Ok();
    }
    case sensor_cmd_t::ADD_CONTACT: cmd->kind = Command::Kind::kAddContactSensor; return Status::Ok();
    case sensor_cmd_t::REMOVE: cmd->kind = Command::Kind::kRemoveSensor; return Status::Ok();
    default:
      return Status::InvalidArgument("unknown sensor_cmd_t op " + std::to_string(m.op) +
                                     " (ADD_RANGE 1, ADD_CONTACT 2, REMOVE 3)");
  }
}

Status DecodeRayCast(const ray_cast_t& m, int max_rays, Command* cmd) {
  cmd->kind = Command::Kind::kRayCast;
  if (m.num_rays < 1) return Status::InvalidArgument("num_rays must be >= 1, got " + std::to_string(m.num_rays));
  if (m.num_rays > max_rays) {
    return Status::ResourceExhausted("num_rays " + std::to_string(m.num_rays) + " exceeds max_rays_per_cast = " +
                                     std::to_string(max_rays));
  }
  auto rays = std::make_shared<std::vector<Ray>>(m.num_rays);
  for (int i = 0; i < m.num_rays; ++i) {
    const Status st = MakeRay(Read3(m.origins[i].data()), Read3(m.directions[i].data()), m.max_distances[i],
                              &(*rays)[i]);
    if (!st.ok()) return Status::InvalidArgument("ray " + std::to_string(i) + ": " + st.message());
  }
  cmd->rays = std::move(rays);
  cmd->ray_options.ignore = m.ignore_ids;
  if (m.collision_mask < 0 || m.collision_mask > 0xFFFFFFFFll) {
    return Status::InvalidArgument("collision_mask " + std::to_string(m.collision_mask) +
                                   " must be 0 (every body) or a 32-bit mask");
  }
  if (m.collision_mask != 0) cmd->ray_options.mask = static_cast<uint32_t>(m.collision_mask);
  return Status::Ok();
}

}  // namespace contactsim
