// Bodies resting on a jointed support, under every registered method: a
// plank that hangs from a hinge (a balance), welded to the world on a slope,
// or swung on two rods (a parallel swing), carrying 1 to 5 boxes of 0.1 to
// 10 kg. Static friction must hold a box on a moving support exactly as it
// holds one on the ground: with the boxes fixed on the plank, the support
// and its load move as one rigid body, whose motion is known in closed form.
//
//   balance   a rigid pendulum: released level, its centre of mass c off
//             the vertical through the pivot by theta_eq = atan(c_x / -c_z)
//             (plank frame), it swings between 0 and 2 theta_eq (energy
//             conservation; any damping swings it less, never more)
//   weld      the plank does not move; a box on a slope with tan < mu stays
//   swing     two rods of equal length keep the plank level (a
//             parallelogram), so the boxes see only a bounded acceleration
//             (g sin of the swing's amplitude), which mu holds
//   slider    the level plank slides freely down a rail (a prismatic joint)
//             inclined by beta, accelerating at g sin(beta) along it; in the
//             plank's frame a box feels g cos(beta) tilted by beta from the
//             plank's normal, which tan(beta) < mu holds
//   slide     loads too heavy for the balance's friction slide off onto the
//             ground: nothing becomes non-finite, no energy appears, the
//             hinge stays closed
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/method_support.h"
#include "service/physics/body_settings.h"
#include "service/physics/runaway_watch.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddGround;
using testing::AddValidBody;
using testing::MethodConfig;

constexpr double kPlankHalf[3] = {0.5, 0.1, 0.02};  // m
constexpr double kBoxHalf = 0.04;                  // m
constexpr double kHangHeight = 0.4;                // m, pivot above the plank's centre
constexpr double kSeconds = 3.0;
// Bounds every method meets on the held loads (the ground's own incline
// holds a box to 1e-6 m; here the 0.1 mm fall onto the plank comes first).
constexpr double kMaxCreep = 0.5e-3;         // m, a box's motion on the plank
constexpr double kMaxOverswing = 0.25 * M_PI / 180;  // rad, beyond 2 theta_eq
constexpr double kMaxJointOpening = 0.5e-3;  // m, largest anchor separation
// The swing's own T + V oscillates under the semi-implicit step by about
// omega h / 2 of its kinetic energy (omega = sqrt(g / l), 0.9% here), the
// bounded error of a symplectic integrator, under every method alike.
constexpr double kMaxEnergyGain = 1e-2;      // of EnergyScale, largest rise of T + V
// The boxes rest 0.1 mm above the plank (a barrier method pushes a flush
// start apart by hopping).
constexpr double kGap = 1e-4;

struct SupportScene {
  BodyId plank = 0;
  std::vector<BodyId> boxes;
};

BodyId AddPlank(World& world, const Vec3& centre, double mu, double mass, const Quat& q, const Vec3& v) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3(kPlankHalf[0], kPlankHalf[1], kPlankHalf[2]);
  s.position = centre;
  s.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  s.mass = mass;
  s.friction = mu;
  s.restitution = 0.0;
  s.linear_velocity = v;
  return AddValidBody(world, s);
}

// A box of mass m resting on the plank's top face at plank-frame offset x,
// moving with velocity v.
BodyId AddLoad(World& world, const RigidBody& plank, double x, double m, double mu, const Vec3& v) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3::Constant(kBoxHalf);
  const Vec3 local(x, 0.0, kPlankHalf[2] + kBoxHalf + kGap);
  s.position = plank.x + plank.q * local;
  s.orientation = Eigen::Vector4d(plank.q.w(), plank.q.x(), plank.q.y(), plank.q.z());
  s.mass = m;
  s.friction = mu;
  s.restitution = 0.0;
  s.linear_velocity = v;
  return AddValidBody(world, s);
}

// Where the boxes sit: n boxes spread evenly over the plank, shifted by
// `offset` (m) along it.
std::vector<double> LoadPositions(int n, double offset) {
  std::vector<double> x;
  const double span = 2.0 * (kPlankHalf[0] - 2.0 * kBoxHalf - std::abs(offset));
  for (int i = 0; i < n; ++i) x.push_back(offset + (n == 1 ? 0.0 : -0.5 * span + span * i / (n - 1)));
  return x;
}

// Largest distance (m) a box moved in the plank's frame since the start.
double Creep(const World& world, const SupportScene& scene, const std::vector<Vec3>& start) {
  const RigidBody& p = *world.Find(scene.plank);
  double worst = 0.0;
  for (size_t i = 0; i < scene.boxes.size(); ++i) {
    const Vec3 local = p.q.inverse() * (world.Find(scene.boxes[i])->x - p.x);
    worst = std::max(worst, (local - start[i]).norm());
  }
  return worst;
}

std::vector<Vec3> LocalPositions(const World& world, const SupportScene& scene) {
  const RigidBody& p = *world.Find(scene.plank);
  std::vector<Vec3> out;
  for (BodyId b : scene.boxes) out.push_back(p.q.inverse() * (world.Find(b)->x - p.x));
  return out;
}

// Plank's tilt about the hinge axis y (rad), from its long axis.
double Tilt(const World& world, BodyId plank) {
  const Vec3 ax = world.Find(plank)->q * Vec3::UnitX();
  return std::atan2(-ax.z(), ax.x());
}

// Equilibrium tilt of the rigid balance: its centre of mass below the pivot.
double EquilibriumTilt(const World& world, const Vec3& pivot) {
  double m = 0.0;
  Vec3 c = Vec3::Zero();
  for (const RigidBody& b : world.bodies()) {
    if (!b.IsDynamic()) continue;
    m += b.mass;
    c += b.mass * (b.x - pivot);
  }
  c /= m;
  // turning by theta about y takes c = (cx, 0, cz) to x' = cx cos + cz sin,
  // zero (below the pivot, cz < 0) at tan theta = cx / -cz
  return std::atan2(c.x(), -c.z());
}

// What a run measured.
struct SupportRun {
  double creep = 0.0;        // m, largest box motion on the plank
  double max_tilt = 0.0;     // rad, largest plank tilt (signed toward theta_eq)
  double theta_eq = 0.0;     // rad
  double joint_error = 0.0;  // m, largest anchor separation
  double energy_gain = 0.0;  // J, largest rise of the mechanical energy above its start
  double max_speed = 0.0;    // m/s
  bool finite = true;
  std::string blowup;        // the watch's message, "" if it never tripped
};

// Largest opening (m) of the world's joints: a prismatic joint's anchors
// apart across its axis (along it they slide), any other joint's anchors
// apart.
double JointOpening(const World& world) {
  double worst = 0.0;
  for (const Joint& j : world.joints()) {
    const RigidBody* a = world.Find(j.body_a);
    const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
    Vec3 apart = AnchorWorld(j.anchor_a, a) - AnchorWorld(j.anchor_b, b);
    if (j.kind == JointKind::kPrismatic) {
      const Vec3 axis = a->q * j.axis_a;
      apart -= apart.dot(axis) * axis;
    }
    worst = std::max(worst, apart.norm());
  }
  return worst;
}

void Record(const World& world, double e0, SupportRun* run) {
  run->joint_error = std::max(run->joint_error, JointOpening(world));
  run->energy_gain = std::max(run->energy_gain, testing::MechanicalEnergy(world) - e0);
  for (const RigidBody& b : world.bodies()) {
    if (!IsFinite(b.x) || !IsFinite(b.q) || !IsFinite(b.P) || !IsFinite(b.L)) run->finite = false;
    if (b.IsDynamic()) run->max_speed = std::max(run->max_speed, b.LinearVelocity().norm());
  }
}

enum class Support { kBalance, kWeld, kSwing, kSlide, kSlider };
const char* SupportName(Support s) {
  switch (s) {
    case Support::kBalance: return "balance";
    case Support::kWeld: return "weld";
    case Support::kSwing: return "swing";
    case Support::kSlide: return "slide";
    case Support::kSlider: return "slider";
  }
  return "?";
}

struct Load {
  int n;
  double mass;    // kg, each box
  double offset;  // m, of the loads along the plank
};

constexpr double kRod = 0.5;        // m, the swing's rods
constexpr double kSwingSpeed = 1.0;  // m/s, the swing's start: about 26 degrees of swing

// A rod of the swing: a thin capsule hanging from the world at `top`, hinged
// about y at both ends, turning at w about y (its lower end moving at v).
void AddRod(World& world, BodyId plank, const Vec3& top, double v) {
  BodySettings s;
  s.shape = ShapeType::kCapsule;
  s.radius = 0.01;
  s.half_length = 0.5 * kRod - 0.01;
  s.position = top - Vec3(0, 0, 0.5 * kRod);
  s.mass = 0.2;
  s.linear_velocity = Vec3(0.5 * v, 0, 0);
  s.angular_velocity = Vec3(0, -v / kRod, 0);  // the lower end moves +x
  const BodyId rod = AddValidBody(world, s);
  testing::AddHinge(world, rod, kWorldBody, top, Vec3::UnitY());
  testing::AddHinge(world, rod, plank, top - Vec3(0, 0, kRod), Vec3::UnitY());
}

// "balance n=5 m=10 off=0.02 plank=0.5", as kKnownMisses lists a case.
std::string CaseId(Support support, const Load& load, double plank_mass) {
  char text[96];
  std::snprintf(text, sizeof text, "%s n=%d m=%g off=%g plank=%g", SupportName(support), load.n, load.mass,
                load.offset, plank_mass);
  return text;
}

// Builds the support with its loads; `pivot` is the balance's hinge point.
// The boxes and the plank collide only with each other (and the slide's
// ground): the rods and the hinge sit clear of them.
SupportScene Build(World& w, Support support, const Load& load, double mu, double plank_mass, Vec3* pivot) {
  SupportScene scene;
  const Vec3 centre(0, 0, 1.0);
  *pivot = centre + Vec3(0, 0, kHangHeight);
  if (support == Support::kSlide) AddGround(w, 0.0, mu);
  const double slope = support == Support::kWeld ? 0.8 * std::atan(mu) : 0.0;
  const Vec3 v = support == Support::kSwing ? Vec3(kSwingSpeed, 0, 0) : Vec3::Zero();
  scene.plank = AddPlank(w, centre, mu, plank_mass, Quat(Eigen::AngleAxisd(slope, Vec3::UnitY())), v);
  const RigidBody plank = *w.Find(scene.plank);
  for (double x : LoadPositions(load.n, load.offset)) scene.boxes.push_back(AddLoad(w, plank, x, load.mass, mu, v));
  switch (support) {
    case Support::kBalance:
    case Support::kSlide:
      testing::AddHinge(w, scene.plank, kWorldBody, *pivot, Vec3::UnitY());
      break;
    case Support::kWeld:
      testing::AddJoint(w, JointKind::kFixed, scene.plank, kWorldBody, centre);
      break;
    case Support::kSwing:  // outside the plank's ends, so the rods miss the boxes
      for (double x : {-kPlankHalf[0], kPlankHalf[0]}) AddRod(w, scene.plank, centre + Vec3(x, 0.2, kRod), kSwingSpeed);
      break;
    case Support::kSlider: {  // a rail inclined as the weld's slope, down toward +x
      const double beta = 0.8 * std::atan(mu);
      JointSettings rail;
      rail.kind = JointKind::kPrismatic;
      rail.body_a = scene.plank;
      rail.body_b = kWorldBody;
      rail.anchor = centre;
      rail.axis = Vec3(std::cos(beta), 0.0, -std::sin(beta));
      testing::AddJoint(w, rail);
      break;
    }
  }
  return scene;
}

// Steps `seconds` and measures.
SupportRun RunSupport(testing::MethodSim& sim, const SupportScene& scene, const Vec3& pivot, double seconds) {
  SupportRun run;
  run.theta_eq = EquilibriumTilt(sim.world, pivot);
  const std::vector<Vec3> start = LocalPositions(sim.world, scene);
  const double e0 = testing::MechanicalEnergy(sim.world);
  const double sign = run.theta_eq < 0.0 ? -1.0 : 1.0;
  RunawayWatch watch;
  while (sim.world.time < seconds) {
    watch.BeforeStep(sim.world);
    sim.Step();
    Record(sim.world, e0, &run);
    const Status st = watch.AfterStep(sim.world);
    if (!st.ok()) run.blowup = st.message();
    if (!run.finite || !st.ok()) break;
    run.creep = std::max(run.creep, Creep(sim.world, scene, start));
    run.max_tilt = std::max(run.max_tilt, sign * Tilt(sim.world, scene.plank));
  }
  return run;
}

class JointedSupportTest : public ::testing::TestWithParam<MethodConfig> {};

// The scene's energy scale (J): every dynamic body lifted by 0.1 m, for
// bounds on an energy gain.
double EnergyScale(const World& world) {
  double e = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic()) e += b.mass * world.gravity.norm() * 0.1;
  }
  return e;
}

// Loads that mu = 0.9 holds at twice their balance's equilibrium tilt (the
// largest swing), from a light box to five heavy ones, centred and off
// centre, on a plank 2 kg and 0.5 kg heavy (up to 100 times lighter than
// its load).
constexpr Load kHeldLoads[] = {{1, 1.0, 0.0}, {2, 1.0, 0.0}, {3, 0.1, 0.05}, {5, 10.0, 0.02}, {2, 5.0, 0.04},
                               {1, 0.1, 0.2}};
constexpr double kPlankMasses[] = {2.0, 0.5};

// Verifies that static friction holds every load on a balance, a welded
// slope and a parallel swing as it holds it on the ground: no box moves on
// the plank by more than kMaxCreep (the 0.1 mm fall onto it included), the
// balance swings no further than the rigid pendulum's 2 theta_eq, the joints
// stay closed, no energy appears and the blow-up watch never trips.
TEST_P(JointedSupportTest, StaticFrictionHoldsOnJointedSupports) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (Support support : {Support::kBalance, Support::kWeld, Support::kSwing}) {
    for (double plank_mass : kPlankMasses) {
      for (const Load& load : kHeldLoads) {
        testing::MethodSim sim(config.method, config.params);
        Vec3 pivot;
        const SupportScene scene = Build(sim.world, support, load, 0.9, plank_mass, &pivot);
        if (testing::RefusedByContract(config, sim.world, ContractOf(config).joints, "joints")) return;
        const SupportRun r = RunSupport(sim, scene, pivot, kSeconds);
        const double scale = EnergyScale(sim.world);
        const std::string id = CaseId(support, load, plank_mass);
        std::printf("%-9s %s: creep %.3g mm, tilt %.3g deg (2 eq %.3g), joint %.3g mm, dE %.3g of %.3g J, %s\n",
                    config.label.c_str(), id.c_str(), 1e3 * r.creep, r.max_tilt * 180 / M_PI,
                    2 * r.theta_eq * 180 / M_PI, 1e3 * r.joint_error, r.energy_gain, scale,
                    r.blowup.empty() ? "no blow-up" : r.blowup.c_str());
        ASSERT_TRUE(r.finite && r.blowup.empty()) << id << ": " << r.blowup;
        checks.Expect(id + " creep", r.creep, 0.0, kMaxCreep);
        if (support == Support::kBalance) {
          checks.Expect(id + " swing", std::max(0.0, r.max_tilt - 2.0 * r.theta_eq), 0.0, kMaxOverswing);
        }
        checks.Expect(id + " joint", r.joint_error, 0.0, kMaxJointOpening);
        checks.Expect(id + " energy", std::max(0.0, r.energy_gain), 0.0, kMaxEnergyGain * scale);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that static friction holds every load of the test above on a
// plank sliding freely down an inclined rail (a prismatic joint, tan(beta)
// = 0.8 mu), over the same masses, counts and planks: no box moves on the
// plank by more than kMaxCreep, the rail stays closed and no energy appears.
TEST_P(JointedSupportTest, StaticFrictionHoldsOnASlidingSupport) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (double plank_mass : kPlankMasses) {
    for (const Load& load : kHeldLoads) {
      testing::MethodSim sim(config.method, config.params);
      Vec3 pivot;
      const SupportScene scene = Build(sim.world, Support::kSlider, load, 0.9, plank_mass, &pivot);
      if (testing::RefusedByContract(config, sim.world, ContractOf(config).joints, "joints")) return;
      const SupportRun r = RunSupport(sim, scene, pivot, kSeconds);
      const double scale = EnergyScale(sim.world);
      const std::string id = CaseId(Support::kSlider, load, plank_mass);
      std::printf("%-9s %s: creep %.3g mm, joint %.3g mm, dE %.3g of %.3g J, %s\n", config.label.c_str(), id.c_str(),
                  1e3 * r.creep, 1e3 * r.joint_error, r.energy_gain, scale,
                  r.blowup.empty() ? "no blow-up" : r.blowup.c_str());
      ASSERT_TRUE(r.finite && r.blowup.empty()) << id << ": " << r.blowup;
      checks.Expect(id + " creep", r.creep, 0.0, kMaxCreep);
      checks.Expect(id + " joint", r.joint_error, 0.0, kMaxJointOpening);
      checks.Expect(id + " energy", std::max(0.0, r.energy_gain), 0.0, kMaxEnergyGain * scale);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that loads too heavy and too far out for mu = 0.2 slide off a
// balance onto the ground without a blow-up: every state finite, the watch
// silent, no energy gained, the hinge closed, and no body faster than a fall
// from the plank allows.
TEST_P(JointedSupportTest, LoadsSlideOffWithoutBlowingUp) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (double plank_mass : {2.0, 0.2}) {
    for (const Load& load : {Load{1, 10.0, 0.3}, Load{3, 10.0, 0.2}, Load{2, 5.0, 0.25}, Load{5, 1.0, 0.1}}) {
      testing::MethodSim sim(config.method, config.params);
      Vec3 pivot;
      const SupportScene scene = Build(sim.world, Support::kSlide, load, 0.2, plank_mass, &pivot);
      if (testing::RefusedByContract(config, sim.world, ContractOf(config).joints, "joints")) return;
      const SupportRun r = RunSupport(sim, scene, pivot, kSeconds);
      const double scale = EnergyScale(sim.world);
      const std::string id = CaseId(Support::kSlide, load, plank_mass);
      std::printf("%-9s %s: joint %.3g mm, dE %.3g of %.3g J, fastest %.3g m/s, %s\n", config.label.c_str(),
                  id.c_str(), 1e3 * r.joint_error, r.energy_gain, scale, r.max_speed,
                  r.blowup.empty() ? "no blow-up" : r.blowup.c_str());
      ASSERT_TRUE(r.finite && r.blowup.empty()) << id << ": " << r.blowup;
      // the fastest a body can fall: from the plank's end (1.5 m up) to the ground
      EXPECT_LT(r.max_speed, std::sqrt(2.0 * 9.81 * 1.5) + 0.5) << id;
      checks.Expect(id + " joint", r.joint_error, 0.0, kMaxJointOpening);
      checks.Expect(id + " energy", std::max(0.0, r.energy_gain), 0.0, kMaxEnergyGain * scale);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, JointedSupportTest, ::testing::ValuesIn(testing::JointedWorldConfigs()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
