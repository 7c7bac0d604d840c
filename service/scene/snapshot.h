// Snapshots: the engine's full state <-> binary protobuf
// (service/proto/snapshot.proto). A snapshot holds every state bit of every
// body (x, q, P, L, the last accumulated force and torque, kinematic
// velocities, mass and inertia as stored, the convex hull as built), the
// clock, gravity, dt, the timed wrenches, the next id, the sleep settings
// and each body's rest timer and sleeping island, and the contact
// method's name, parameters and caches (ContactMethod::SaveState), so a run
// restored from it continues bit for bit as the original did.
#pragma once

#include <memory>
#include <string>

#include "service/contact/contact_method.h"
#include "service/physics/world.h"
#include "service/proto/snapshot.pb.h"

namespace contactsim {

void SaveSnapshot(const World& world, const ContactMethod& method, proto::Snapshot* out);

// Rebuilds the world and a new method from a snapshot and checks the world
// against the stored state hash. On error the message names the field, and
// *world and *method are untouched.
Status LoadSnapshot(const proto::Snapshot& snapshot, World* world, std::shared_ptr<ContactMethod>* method);

// Binary protobuf files. WriteSnapshotFile writes a temporary file and
// renames it, so a reader never sees half a snapshot; with `sync` the file
// and its folder are fsynced first (durable across a power loss).
Status WriteSnapshotFile(const std::string& path, const proto::Snapshot& snapshot, bool sync);
Status ReadSnapshotFile(const std::string& path, proto::Snapshot* snapshot);

}  // namespace contactsim
