// Ray casts and sensors of contactsim::Client: ray_cast_t on
// <prefix>_RAY_CAST, answered on RAY_HITS before the reply, and
// sensor_cmd_t on <prefix>_SENSOR_CMD. The server checks every number.
#include <algorithm>

#include "contactsim/client.h"

#include "contactsim/protocol.hpp"

namespace contactsim {
namespace {

std::vector<std::vector<double>> Rows(const std::vector<Eigen::Vector3d>& v) {
  std::vector<std::vector<double>> out;
  out.reserve(v.size());
  for (const Eigen::Vector3d& p : v) out.push_back({p.x(), p.y(), p.z()});
  return out;
}

}  // namespace

Result<ray_hits_t> Client::RayCast(const std::vector<Eigen::Vector3d>& origins,
                                   const std::vector<Eigen::Vector3d>& directions,
                                   const std::vector<double>& max_distances, const std::vector<int64_t>& ignore) {
  Result<ray_hits_t> out;
  if (directions.size() != origins.size() || (max_distances.size() != 1 && max_distances.size() != origins.size())) {
    out.status.code = ReplyCode::kInvalidArgument;
    out.status.message = "RayCast: give one direction per origin and one max distance, or one per origin";
    return out;
  }
  ray_cast_t command{};
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  command.num_rays = static_cast<int32_t>(origins.size());
  command.origins = Rows(origins);
  command.directions = Rows(directions);
  command.max_distances = max_distances.size() == 1 ? std::vector<double>(origins.size(), max_distances[0])
                                                    : max_distances;
  command.num_ignore = static_cast<int32_t>(ignore.size());
  command.ignore_ids = ignore;
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  out.status = Publish(Channel(protocol::kRayCast), command.request_id, buffer.data(),
                       static_cast<int>(buffer.size()));
  std::unique_lock<std::mutex> lock(mutex_);
  if (out.status.ok()) {
    // published before the reply; wait in case the two were reordered
    changed_.wait_for(lock, options_.reply_timeout, [&] { return ray_hits_.count(command.request_id) > 0; });
    auto it = ray_hits_.find(command.request_id);
    if (it == ray_hits_.end()) {
      out.status.code = ReplyCode::kTimeout;
      out.status.message = "no RAY_HITS for request " + std::to_string(command.request_id);
    } else {
      out.value = std::move(it->second);
    }
  }
  ray_hits_.erase(command.request_id);
  return out;
}

CommandResult Client::AddRangeSensor(int64_t body, const std::string& name,
                                     const std::vector<Eigen::Vector3d>& directions, double max_distance,
                                     const Eigen::Vector3d& origin) {
  sensor_cmd_t command{};
  command.op = sensor_cmd_t::ADD_RANGE;
  command.name = name;
  command.body_id = body;
  std::copy(origin.data(), origin.data() + 3, command.origin);
  command.num_rays = static_cast<int32_t>(directions.size());
  command.directions = Rows(directions);
  command.max_distance = max_distance;
  return Send(command);
}

CommandResult Client::AddContactSensor(int64_t body, const std::string& name) {
  sensor_cmd_t command{};
  command.op = sensor_cmd_t::ADD_CONTACT;
  command.name = name;
  command.body_id = body;
  return Send(command);
}

CommandResult Client::RemoveSensor(const std::string& name) {
  sensor_cmd_t command{};
  command.op = sensor_cmd_t::REMOVE;
  command.name = name;
  return Send(command);
}

CommandResult Client::Send(sensor_cmd_t command) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kSensorCmd), command.request_id, buffer.data(),
                 static_cast<int>(buffer.size()));
}

}  // namespace contactsim
