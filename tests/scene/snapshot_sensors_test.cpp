// Sensors in snapshots: saved and loaded with the world in their order, bit
// for bit; a snapshot with a bad sensor is refused naming it, and the world
// loaded into is left as it was. Removing a body removes its sensors.
#include "service/scene/snapshot_sensors.h"

#include <gtest/gtest.h>

#include "service/contact/impulse/impulse_method.h"
#include "service/scene/snapshot.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

World SensedWorld() {
  World w;
  testing::AddGround(w, 0.0, 0.5);
  const BodyId box = testing::AddBox(w, Vec3(0.1, 0.2, 0.3), Vec3(0, 0, 0.3), 0.0, 0.5);
  const BodyId ball = testing::AddSphere(w, 0.1, Vec3(1, 0, 1), 0.0);
  w.sensors.ranges.push_back({"lidar", box, Vec3(0, 0, 0.3), {Vec3(1, 0, 0), Vec3(0.6, 0.8, 0)}, 5.0});
  w.sensors.contacts.push_back({"foot", box});
  w.sensors.contacts.push_back({"hand", ball});
  return w;
}

// Verifies a snapshot round trip keeps every sensor, in order, bit for bit.
TEST(SnapshotSensorsTest, RoundTripKeepsTheSensors) {
  const World w = SensedWorld();
  ImpulseMethod method;
  proto::Snapshot snap;
  SaveSnapshot(w, method, &snap);
  World loaded;
  std::shared_ptr<ContactMethod> m;
  ASSERT_TRUE(LoadSnapshot(snap, &loaded, &m).ok());
  ASSERT_EQ(loaded.sensors.ranges.size(), 1u);
  const RangeSensor& r = loaded.sensors.ranges[0];
  EXPECT_EQ(r.name, "lidar");
  EXPECT_EQ(r.body, 2);
  EXPECT_EQ(r.origin, Vec3(0, 0, 0.3));
  EXPECT_EQ(r.directions, w.sensors.ranges[0].directions);
  EXPECT_EQ(r.max_distance, 5.0);
  ASSERT_EQ(loaded.sensors.contacts.size(), 2u);
  EXPECT_EQ(loaded.sensors.contacts[0].name, "foot");
  EXPECT_EQ(loaded.sensors.contacts[1].name, "hand");
  EXPECT_EQ(loaded.sensors.contacts[1].body, 3);
}

// Verifies bad sensors in a snapshot are refused with their name, and the
// world keeps its own sensors.
TEST(SnapshotSensorsTest, BadSensorsAreRefusedByName) {
  const World w = SensedWorld();
  ImpulseMethod method;
  proto::Snapshot good;
  SaveSnapshot(w, method, &good);
  struct Case {
    const char* what;
    void (*spoil)(proto::Snapshot*);
    const char* words;
  };
  const Case cases[] = {
      {"missing body", [](proto::Snapshot* s) { s->mutable_contact_sensors(0)->set_body(99); }, "no body 99"},
      {"bad name", [](proto::Snapshot* s) { s->mutable_contact_sensors(1)->set_name("a b"); }, "may hold only"},
      {"twice", [](proto::Snapshot* s) { s->mutable_contact_sensors(1)->set_name("lidar"); }, "taken twice"},
      {"zero ray", [](proto::Snapshot* s) { s->mutable_range_sensors(0)->set_directions(0, 0.0); }, "direction 0"},
      {"nan range",
       [](proto::Snapshot* s) { s->mutable_range_sensors(0)->set_max_distance(std::nan("")); }, "max_distance"},
      {"short origin", [](proto::Snapshot* s) { s->mutable_range_sensors(0)->mutable_origin()->RemoveLast(); },
       "origin"},
      {"ragged rays", [](proto::Snapshot* s) { s->mutable_range_sensors(0)->add_directions(1.0); }, "3 numbers"},
  };
  for (const Case& c : cases) {
    proto::Snapshot bad = good;
    c.spoil(&bad);
    World target = SensedWorld();
    target.sensors.contacts.pop_back();
    std::shared_ptr<ContactMethod> m;
    const Status st = LoadSnapshot(bad, &target, &m);
    EXPECT_FALSE(st.ok()) << c.what;
    EXPECT_NE(st.message().find(c.words), std::string::npos) << c.what << ": " << st.message();
    EXPECT_NE(st.message().find("sensor"), std::string::npos) << st.message();
    EXPECT_EQ(target.sensors.contacts.size(), 1u) << c.what;
  }
}

// Verifies removing a body removes the sensors on it and only those, and
// Clear removes every sensor.
TEST(SnapshotSensorsTest, RemovingABodyRemovesItsSensors) {
  World w = SensedWorld();
  ASSERT_TRUE(w.RemoveBody(2).ok());
  EXPECT_TRUE(w.sensors.ranges.empty());
  ASSERT_EQ(w.sensors.contacts.size(), 1u);
  EXPECT_EQ(w.sensors.contacts[0].name, "hand");
  EXPECT_EQ(w.sensors.Remove("nope").code(), StatusCode::kNotFound);
  EXPECT_TRUE(w.sensors.Remove("hand").ok());
  EXPECT_TRUE(w.sensors.empty());
  w = SensedWorld();
  w.Clear();
  EXPECT_TRUE(w.sensors.empty());
}

}  // namespace
}  // namespace contactsim
