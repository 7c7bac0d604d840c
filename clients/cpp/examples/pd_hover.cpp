// Holds a 2 kg box at a target height with a PD controller that pushes it
// through forces, in lockstep with the server: every step waits for this
// process's input, computed from the STATE of the step before.
//
//   F_z = m g + kp (z* - z) - kd v_z,   kp = m w^2, kd = 2 m w  (critical damping)
//
// With w = 2 pi 1.5 rad/s the error falls as (1 + w t) e^(-w t): from 0.4 m
// to below 1 cm in about 0.6 s. Exits 0 when the box ends within 1 cm of the
// target, 1 otherwise.
//
//   contactsim-example-pd-hover [--lcm-url URL] [--prefix NAME] [--seconds S] [--target Z]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "contactsim/client.h"
#include "contactsim/controller.h"

namespace {

constexpr double kMass = 2.0;                   // kg
constexpr double kHalf = 0.1;                   // m, half extent of the box
constexpr double kGravity = 9.81;               // m/s^2
constexpr double kOmega = 2.0 * M_PI * 1.5;     // rad/s, closed-loop natural frequency
constexpr double kP = kMass * kOmega * kOmega;  // N/m
constexpr double kD = 2.0 * kMass * kOmega;     // N s/m

bool Check(const contactsim::CommandResult& result, const char* what) {
  if (result.ok()) return true;
  std::fprintf(stderr, "%s failed: %s\n", what, contactsim::ToString(result).c_str());
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  contactsim::ClientOptions options;
  double seconds = 3.0, target = 0.5;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--lcm-url") == 0) options.url = argv[i + 1];
    else if (std::strcmp(argv[i], "--prefix") == 0) options.prefix = argv[i + 1];
    else if (std::strcmp(argv[i], "--seconds") == 0) seconds = std::atof(argv[i + 1]);
    else if (std::strcmp(argv[i], "--target") == 0) target = std::atof(argv[i + 1]);
  }
  options.reply_timeout = std::chrono::milliseconds(5000);
  contactsim::Client client(options);
  if (!client.WaitForServer(std::chrono::seconds(10))) {
    std::fprintf(stderr, "no server on %s_STATUS\n", client.prefix().c_str());
    return 1;
  }
  if (!Check(client.Pause(), "pause") || !Check(client.Reset(), "reset")) return 1;
  if (!Check(client.AddPlane(Eigen::Vector3d::UnitZ(), 0.0).status, "add plane")) return 1;
  contactsim::BodyOptions box;
  box.position = Eigen::Vector3d(0, 0, kHalf);
  box.mass = kMass;
  const auto id = client.AddBox(Eigen::Vector3d::Constant(kHalf), box);
  if (!Check(id.status, "add box")) return 1;
  const double dt = 1.0 / 240.0;
  const int64_t steps = static_cast<int64_t>(std::llround(seconds / dt));

  contactsim::Controller controller(client, [&](const contactsim::state_t& s) {
    contactsim::BodyInputs inputs;
    for (const auto& b : s.bodies) {
      if (b.id != id.value) continue;
      const double z = b.position[2], vz = b.linear_velocity[2];
      inputs[b.id].force = Eigen::Vector3d(0, 0, kMass * kGravity + kP * (target - z) - kD * vz);
      if (s.step % 120 == 0) std::printf("t %6.3f s  z %.4f m  v %+.4f m/s\n", s.time, z, vz);
    }
    return inputs;
  });
  if (!Check(controller.Start(contactsim::LatePolicy::kWait), "register controller")) return 1;
  if (!Check(client.SetMode(contactsim::Mode::kLockstep), "lockstep mode")) return 1;
  // STEP n rather than RESUME then PAUSE: the run ends at step n exactly, however
  // quickly the server steps while a PAUSE would travel.
  const bool reached = Check(client.Step(static_cast<int32_t>(steps)), "step");
  Check(controller.Stop(), "release controller");
  const auto last = client.LatestState();
  if (!reached || !last) {
    std::fprintf(stderr, "lockstep stopped at step %lld of %lld\n", static_cast<long long>(controller.answered()),
                 static_cast<long long>(steps));
    return 1;
  }
  double z = 0.0;
  for (const auto& b : last->bodies) if (b.id == id.value) z = b.position[2];
  std::printf("final: step %lld  z %.4f m  target %.4f m  error %.2e m\n", static_cast<long long>(last->step), z,
              target, z - target);
  return std::abs(z - target) < 0.01 ? 0 : 1;
}
