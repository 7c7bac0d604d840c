// Drops a ball (restitution 0.5) from 1 m onto a plane and prints the apex
// of every bounce. With restitution e each apex is e^2 = 0.25 of the one
// before: 1 m, 0.25 m, 0.0625 m, ...
//
//   contactsim-example-drop-ball [--lcm-url URL] [--prefix NAME] [--seconds S]
//
// The example steps the server itself (STEP 1 per sample), so it works the
// same whether the server runs in realtime or free-run mode, and leaves the
// world paused.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>

#include "contactsim/client.h"

namespace {

constexpr double kRadius = 0.1;      // m
constexpr double kDropHeight = 1.0;  // m, lowest point above the plane
constexpr double kRestitution = 0.5;

bool Check(const contactsim::CommandResult& result, const char* what) {
  if (result.ok()) return true;
  std::fprintf(stderr, "%s failed: %s\n", what,
               contactsim::ToString(result).c_str());
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  contactsim::ClientOptions options;
  double seconds = 3.0;  // simulated time to watch
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--lcm-url") == 0 && has_value) {
      options.url = argv[++i];
    } else if (std::strcmp(argv[i], "--prefix") == 0 && has_value) {
      options.prefix = argv[++i];
    } else if (std::strcmp(argv[i], "--seconds") == 0 && has_value) {
      seconds = std::atof(argv[++i]);
    } else {
      std::fprintf(stderr,
                   "usage: %s [--lcm-url URL] [--prefix NAME] [--seconds S]\n",
                   argv[0]);
      return 2;
    }
  }

  contactsim::Client client(options);
  if (!client.WaitForServer(std::chrono::seconds(5))) {
    std::fprintf(stderr, "no contactsim-server on %s (prefix %s)\n",
                 client.url().c_str(), client.prefix().c_str());
    return 1;
  }
  // Pause first so the ball cannot fall before we start sampling.
  if (!Check(client.Pause(), "pause") || !Check(client.Reset(), "reset")) {
    return 1;
  }

  contactsim::BodyOptions ground;
  ground.restitution = kRestitution;
  ground.name = "ground";
  if (!Check(client.AddPlane(Eigen::Vector3d::UnitZ(), 0.0, ground).status,
             "add plane")) {
    return 1;
  }
  contactsim::BodyOptions ball;
  ball.position = {0.0, 0.0, kDropHeight + kRadius};
  ball.restitution = kRestitution;
  ball.name = "ball";
  const contactsim::Result<int64_t> ball_id = client.AddSphere(kRadius, ball);
  if (!Check(ball_id.status, "add sphere")) return 1;

  std::printf("dropping a %.2f m ball with e = %.2f from %.2f m\n", kRadius,
              kRestitution, kDropHeight);
  // An apex is where the vertical velocity turns from up to down; the
  // highest sampled height of each rise is its apex.
  double previous_vz = 0.0;
  double rise_max = -1.0;
  int bounces = 0;
  double time = 0.0;
  while (time < seconds) {
    if (!Check(client.Step(1), "step")) return 1;
    const std::optional<contactsim::state_t> state = client.LatestState();
    time = state->time;
    for (const contactsim::body_state_t& body : state->bodies) {
      if (body.id != ball_id.value) continue;
      const double height = body.position[2] - kRadius;
      const double vz = body.linear_velocity[2];
      if (vz > 0.0) rise_max = std::max(rise_max, height);
      if (previous_vz > 0.0 && vz <= 0.0 && rise_max >= 0.0) {
        ++bounces;
        std::printf("bounce %d: apex %.4f m at t = %.3f s\n", bounces,
                    rise_max, time);
        rise_max = -1.0;
      }
      previous_vz = vz;
    }
  }
  std::printf("%d bounces in %.2f s\n", bounces, time);
  return 0;
}
