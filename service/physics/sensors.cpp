#include "service/physics/sensors.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace contactsim {

bool Sensors::HasName(const std::string& name) const {
  for (const RangeSensor& s : ranges) {
    if (s.name == name) return true;
  }
  for (const ContactSensor& s : contacts) {
    if (s.name == name) return true;
  }
  return false;
}

Status Sensors::Remove(const std::string& name) {
  const size_t before = ranges.size() + contacts.size();
  ranges.erase(std::remove_if(ranges.begin(), ranges.end(), [&](const RangeSensor& s) { return s.name == name; }),
               ranges.end());
  contacts.erase(
      std::remove_if(contacts.begin(), contacts.end(), [&](const ContactSensor& s) { return s.name == name; }),
      contacts.end());
  if (ranges.size() + contacts.size() == before) return Status::NotFound("no sensor named \"" + name + "\"");
  return Status::Ok();
}

void Sensors::RemoveBody(BodyId body) {
  ranges.erase(std::remove_if(ranges.begin(), ranges.end(), [&](const RangeSensor& s) { return s.body == body; }),
               ranges.end());
  contacts.erase(
      std::remove_if(contacts.begin(), contacts.end(), [&](const ContactSensor& s) { return s.body == body; }),
      contacts.end());
}

Status CheckSensorName(const std::string& name) {
  if (name.empty() || name.size() > 64) {
    return Status::InvalidArgument("sensor name must have 1 to 64 characters, got " + std::to_string(name.size()));
  }
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-')) {
      return Status::InvalidArgument("sensor name \"" + name + "\" may hold only [A-Za-z0-9_.-]");
    }
  }
  return Status::Ok();
}

Status CheckRangeSensor(int max_rays, const RangeSensor& s) {
  const RangeSensor* sensor = &s;
  Status st = CheckSensorName(sensor->name);
  if (!st.ok()) return st;
  if (!IsFinite(sensor->origin)) return Status::InvalidArgument("range sensor origin is not finite");
  const int n = static_cast<int>(sensor->directions.size());
  if (n < 1 || n > max_rays) {
    return Status::InvalidArgument("range sensor needs 1 to " + std::to_string(max_rays) + " rays, got " +
                                   std::to_string(n));
  }
  for (int i = 0; i < n; ++i) {
    const Vec3& d = sensor->directions[i];
    const double length = d.norm();
    if (!IsFinite(d) || !(length > 1e-12)) {
      return Status::InvalidArgument("range sensor direction " + std::to_string(i) +
                                     " must be finite with length > 1e-12");
    }
  }
  if (!std::isfinite(sensor->max_distance) || !(sensor->max_distance > 0.0)) {
    return Status::InvalidArgument("range sensor max_distance " + std::to_string(sensor->max_distance) +
                                   " must be finite and > 0");
  }
  return Status::Ok();
}

void NormaliseDirections(RangeSensor* sensor) {
  for (Vec3& d : sensor->directions) d /= d.norm();
}

}  // namespace contactsim
