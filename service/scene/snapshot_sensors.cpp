#include "service/scene/snapshot_sensors.h"

#include <string>

namespace contactsim {
namespace {

// Far above any server's ray limit, so a snapshot written under one
// configuration loads under another.
constexpr int kMaxSnapshotRays = 1 << 20;

Status Where(const std::string& name, const Status& st) {
  return Status::InvalidArgument("snapshot: sensor \"" + name + "\": " + st.message());
}

Status LoadRange(const proto::SnapshotRangeSensor& in, const World& world, RangeSensor* s) {
  s->name = in.name();
  s->body = in.body();
  s->max_distance = in.max_distance();
  if (in.origin_size() != 3) return Where(s->name, Status::InvalidArgument("origin must hold 3 numbers"));
  s->origin = Vec3(in.origin(0), in.origin(1), in.origin(2));
  if (in.directions_size() % 3 != 0) {
    return Where(s->name, Status::InvalidArgument("directions must hold 3 numbers per ray"));
  }
  for (int i = 0; i + 2 < in.directions_size(); i += 3) {
    s->directions.emplace_back(in.directions(i), in.directions(i + 1), in.directions(i + 2));
  }
  Status st = CheckRangeSensor(kMaxSnapshotRays, *s);
  if (!st.ok()) return Where(s->name, st);
  if (world.Find(s->body) == nullptr) return Where(s->name, Status::InvalidArgument("no body " + std::to_string(s->body)));
  return Status::Ok();
}

}  // namespace

void SaveSensors(const Sensors& sensors, proto::Snapshot* out) {
  for (const RangeSensor& s : sensors.ranges) {
    proto::SnapshotRangeSensor* p = out->add_range_sensors();
    p->set_name(s.name);
    p->set_body(s.body);
    for (int k = 0; k < 3; ++k) p->add_origin(s.origin[k]);
    for (const Vec3& d : s.directions) {
      for (int k = 0; k < 3; ++k) p->add_directions(d[k]);
    }
    p->set_max_distance(s.max_distance);
  }
  for (const ContactSensor& s : sensors.contacts) {
    proto::SnapshotContactSensor* p = out->add_contact_sensors();
    p->set_name(s.name);
    p->set_body(s.body);
  }
}

Status LoadSensors(const proto::Snapshot& snap, World* world) {
  Sensors sensors;
  for (const proto::SnapshotRangeSensor& in : snap.range_sensors()) {
    RangeSensor s;
    Status st = LoadRange(in, *world, &s);
    if (!st.ok()) return st;
    if (sensors.HasName(s.name)) return Where(s.name, Status::InvalidArgument("the name is taken twice"));
    sensors.ranges.push_back(std::move(s));
  }
  for (const proto::SnapshotContactSensor& in : snap.contact_sensors()) {
    ContactSensor s{in.name(), in.body()};
    Status st = CheckSensorName(s.name);
    if (!st.ok()) return Where(s.name, st);
    if (sensors.HasName(s.name)) return Where(s.name, Status::InvalidArgument("the name is taken twice"));
    if (world->Find(s.body) == nullptr) {
      return Where(s.name, Status::InvalidArgument("no body " + std::to_string(s.body)));
    }
    sensors.contacts.push_back(std::move(s));
  }
  world->sensors = std::move(sensors);
  return Status::Ok();
}

}  // namespace contactsim
