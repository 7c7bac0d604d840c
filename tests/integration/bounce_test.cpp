// A ball dropped on the real server, observed through the C++ client.
#include <algorithm>
#include <cmath>
#include <optional>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using BounceTest = ServerTest;

constexpr double kRadius = 0.1;      // m
constexpr double kDropHeight = 1.0;  // m, lowest point above the plane
constexpr double kRestitution = 0.5;
// The rebound apex is e^2 h = 0.25 m. 2% allows for the impulse method's
// collision-time estimate; sampling every step adds at most g dt^2 / 8
// (2e-5 m at dt = 1/240 s), far below that.
constexpr double kApexTolerance = 0.02 * kRestitution * kRestitution * kDropHeight;
constexpr int kMaxSteps = 2000;  // ~8 s at 1/240 s; the apex comes at ~0.7 s

// Verifies a sphere with restitution 0.5 on a plane with restitution 0.5,
// dropped with its lowest point 1 m above the plane, rebounds to 0.25 m.
TEST_F(BounceTest, BallReboundsToRestitutionSquaredTimesDropHeight) {
  BodyOptions ground;
  ground.restitution = kRestitution;
  const Result<int64_t> plane = client_->AddPlane(Eigen::Vector3d::UnitZ(), 0.0, ground);
  ASSERT_TRUE(plane.ok()) << plane.status;
  BodyOptions ball;
  ball.position = {0.0, 0.0, kDropHeight + kRadius};
  ball.restitution = kRestitution;
  const Result<int64_t> ball_id = client_->AddSphere(kRadius, ball);
  ASSERT_TRUE(ball_id.ok()) << ball_id.status;

  // Sample every step: fall, touch, rise, and stop at the first apex (the
  // vertical velocity turning from up to down after the bounce).
  bool bounced = false;
  double previous_vz = 0.0;
  double apex = -1.0;
  double lowest = kDropHeight;
  for (int i = 0; i < kMaxSteps; ++i) {
    const CommandResult step = client_->Step(1);
    ASSERT_TRUE(step.ok()) << step;
    const std::optional<state_t> state = client_->LatestState();
    ASSERT_TRUE(state.has_value());
    std::optional<body_state_t> body;
    for (const body_state_t& b : state->bodies) {
      if (b.id == ball_id.value) body = b;
    }
    ASSERT_TRUE(body.has_value()) << "ball " << ball_id.value << " missing at step "
                                  << state->step;
    const double height = body->position[2] - kRadius;
    const double vz = body->linear_velocity[2];
    lowest = std::min(lowest, height);
    if (vz > 0.0) {
      bounced = true;
      apex = std::max(apex, height);
    }
    if (bounced && previous_vz > 0.0 && vz <= 0.0) break;
    previous_vz = vz;
  }
  ASSERT_TRUE(bounced) << "the ball never moved up; lowest point " << lowest << " m";
  EXPECT_NEAR(apex, kRestitution * kRestitution * kDropHeight, kApexTolerance)
      << "lowest point reached " << lowest << " m";
  // The ball must not sink visibly (5 mm) into the plane on the way.
  EXPECT_GT(lowest, -0.05 * kRadius);
}

}  // namespace
}  // namespace contactsim::testing
