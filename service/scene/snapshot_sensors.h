// The world's sensors (service/physics/sensors.h) in a snapshot.
#pragma once

#include "service/physics/world.h"
#include "service/proto/snapshot.pb.h"

namespace contactsim {

void SaveSensors(const Sensors& sensors, proto::Snapshot* out);

// Reads the sensors of `snap` into world->sensors, checking each as a
// command's would be checked and that its body is in the world; on error
// the message names the sensor and world->sensors is unchanged. Directions
// are kept as saved (already unit), so readings continue bit for bit.
Status LoadSensors(const proto::Snapshot& snap, World* world);

}  // namespace contactsim
