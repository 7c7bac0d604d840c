// Sensors and ray casts: the SimServer methods of the sensor and ray-cast
// channels (sim_server.h).
#include <contactsim/protocol.hpp>

#include <algorithm>

#include "service/contact/method_support.h"
#include "service/server/sensor_messages.h"
#include "service/server/sim_server.h"

namespace contactsim {

Outcome SimServer::ApplySensorCommand(Command& cmd) {
  using K = Command::Kind;
  Sensors& sensors = world_.sensors;
  if (cmd.kind == K::kRemoveSensor) {
    const Status st = sensors.Remove(cmd.sensor_name);
    if (!st.ok()) return Outcome::Failed(st);
    return Outcome::Done("removed sensor \"" + cmd.sensor_name + "\"", true);
  }
  if (world_.Find(cmd.body_id) == nullptr) {
    return Outcome::Failed(Status::NotFound("unknown body id " + std::to_string(cmd.body_id)));
  }
  if (sensors.HasName(cmd.sensor_name)) {
    return Outcome::Failed(Status::InvalidArgument("a sensor named \"" + cmd.sensor_name + "\" exists already"));
  }
  if (cmd.kind == K::kAddRangeSensor) {
    sensors.ranges.push_back(cmd.range_sensor);
    return Outcome::Done("added range sensor \"" + cmd.sensor_name + "\" of " +
                             std::to_string(cmd.range_sensor.directions.size()) + " rays on body " +
                             std::to_string(cmd.body_id),
                         true);
  }
  const Status st = CheckMethodAcceptsContactSensor(method_->Name());
  if (!st.ok()) return Outcome::Failed(st);
  sensors.contacts.push_back({cmd.sensor_name, cmd.body_id});
  return Outcome::Done("added contact sensor \"" + cmd.sensor_name + "\" on body " + std::to_string(cmd.body_id),
                       true);
}

Outcome SimServer::ApplyRayCast(Command& cmd) {
  for (BodyId id : cmd.ray_options.ignore) {
    if (world_.Find(id) == nullptr) {
      return Outcome::Failed(Status::NotFound("ignore_ids: unknown body id " + std::to_string(id)));
    }
  }
  const std::vector<RayHit> hits = RayCastWorld(world_, *cmd.rays, cmd.ray_options, &detector_.runner());
  publisher_.Publish(publisher_.Channel(protocol::kRayHits),
                     MakeRayHitsMessage(cmd.client_id, cmd.request_id, world_, hits));
  const long hit_count = std::count_if(hits.begin(), hits.end(), [](const RayHit& h) { return h.hit; });
  return Outcome::Done("cast " + std::to_string(hits.size()) + " rays, " + std::to_string(hit_count) + " hit",
                       false);
}

void SimServer::PublishSensors() {
  if (world_.sensors.empty()) return;
  publisher_.Publish(publisher_.Channel(protocol::kSensors),
                     MakeSensorsMessage(world_, contacts_, *method_, &detector_.runner()));
}

}  // namespace contactsim
