// The sensors attached to bodies (docs/physics.md, "Ray casts and contact
// sensors"): what each measures, not the readings, which the server takes
// after each step. They belong to the world's content, so a snapshot, the
// journal and an undo keep them with the bodies, and removing a body
// removes its sensors.
#pragma once

#include <string>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/rigid_body.h"
#include "service/physics/status.h"

namespace contactsim {

// A fixed fan of rays from a body (a simple lidar): each step, each ray is
// cast from the body's pose and reads the nearest other body.
struct RangeSensor {
  std::string name;
  BodyId body = 0;
  Vec3 origin = Vec3::Zero();    // m, body frame
  std::vector<Vec3> directions;  // unit, body frame
  double max_distance = 0.0;     // m, > 0
};

// The total contact wrench a body received in the step.
struct ContactSensor {
  std::string name;
  BodyId body = 0;
};

struct Sensors {
  std::vector<RangeSensor> ranges;      // in the order added
  std::vector<ContactSensor> contacts;  // in the order added

  bool empty() const { return ranges.empty() && contacts.empty(); }
  bool HasName(const std::string& name) const;
  // NotFound when no sensor has this name.
  Status Remove(const std::string& name);
  void RemoveBody(BodyId body);
  void Clear() { *this = Sensors{}; }
};

// Checks a sensor before it is added (the body's existence is the world's
// check): a name of [A-Za-z0-9_.-], 1 to 64 characters; for a range sensor
// a finite origin, 1 to `max_rays` finite directions longer than 1e-12, a
// finite max_distance > 0.
Status CheckSensorName(const std::string& name);
Status CheckRangeSensor(int max_rays, const RangeSensor& sensor);
// Scales each direction to unit length (after CheckRangeSensor).
void NormaliseDirections(RangeSensor* sensor);

}  // namespace contactsim
