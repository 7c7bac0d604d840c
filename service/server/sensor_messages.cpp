#include "service/server/sensor_messages.h"

#include "service/contact/contact_wrench.h"
#include "service/server/messages.h"

namespace contactsim {
namespace {

range_reading_t ReadRange(const World& world, const RangeSensor& s, ParallelRunner* runner) {
  range_reading_t r;
  r.name = s.name;
  r.body_id = s.body;
  const RigidBody* body = world.Find(s.body);
  const int n = static_cast<int>(s.directions.size());
  std::vector<Ray> rays(n);
  for (int i = 0; i < n; ++i) {
    rays[i].origin = body->x + body->q * s.origin;
    rays[i].direction = body->q * s.directions[i];
    rays[i].max_distance = s.max_distance;
  }
  RayCastOptions options;
  options.ignore = {s.body};
  const std::vector<RayHit> hits = RayCastWorld(world, rays, options, runner);
  r.num_rays = n;
  r.hit.resize(n);
  r.hit_body_ids.resize(n);
  r.distances.resize(n);
  r.points.assign(n, std::vector<double>(3));
  for (int i = 0; i < n; ++i) {
    const RayHit& h = hits[i];
    r.hit[i] = h.hit;
    r.hit_body_ids[i] = h.body;
    r.distances[i] = h.hit ? h.distance : s.max_distance;
    Copy3(h.hit ? h.point : Vec3(rays[i].origin + s.max_distance * rays[i].direction), r.points[i].data());
  }
  return r;
}

}  // namespace

ray_hits_t MakeRayHitsMessage(const std::string& client_id, int64_t request_id, const World& world,
                              const std::vector<RayHit>& hits) {
  ray_hits_t m;
  m.client_id = client_id;
  m.request_id = request_id;
  m.step = world.step;
  m.time = world.time;
  const int n = static_cast<int>(hits.size());
  m.num_rays = n;
  m.hit.resize(n);
  m.body_ids.resize(n);
  m.points.assign(n, std::vector<double>(3));
  m.normals.assign(n, std::vector<double>(3));
  m.distances.resize(n);
  for (int i = 0; i < n; ++i) {
    m.hit[i] = hits[i].hit;
    m.body_ids[i] = hits[i].body;
    Copy3(hits[i].point, m.points[i].data());
    Copy3(hits[i].normal, m.normals[i].data());
    m.distances[i] = hits[i].distance;
  }
  return m;
}

sensors_t MakeSensorsMessage(const World& world, const ContactSet& contacts, const ContactMethod& method,
                             ParallelRunner* runner) {
  sensors_t m;
  m.time = world.time;
  m.step = world.step;
  for (const RangeSensor& s : world.sensors.ranges) m.ranges.push_back(ReadRange(world, s, runner));
  m.num_ranges = static_cast<int32_t>(m.ranges.size());
  std::vector<BodyId> bodies;
  for (const ContactSensor& s : world.sensors.contacts) bodies.push_back(s.body);
  const std::vector<ContactWrench> wrenches = SumContactWrenches(world, bodies, contacts, method.ValueKind());
  for (size_t i = 0; i < bodies.size(); ++i) {
    contact_reading_t r;
    r.name = world.sensors.contacts[i].name;
    r.body_id = bodies[i];
    r.num_contacts = wrenches[i].contacts;
    Copy3(wrenches[i].normal_force, r.normal_force);
    Copy3(wrenches[i].friction_force, r.friction_force);
    Copy3(wrenches[i].torque, r.torque);
    m.contacts.push_back(r);
  }
  m.num_contacts = static_cast<int32_t>(m.contacts.size());
  return m;
}

}  // namespace contactsim
