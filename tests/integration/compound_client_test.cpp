// Client::AddCompound and the explicit mass properties of BodyOptions
// against a real server: the body lands where its parts say, a bad part is
// refused by name.
#include <cmath>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using CompoundClientTest = ServerTest;

// Verifies a dumbbell of two balls on a rod, given with an explicit centre
// of mass and inertia, is added and reported at the centre of mass, and
// that a plane part is refused naming it.
TEST_F(CompoundClientTest, AddCompoundPlacesItsCentreOfMass) {
  ShapePart ball;
  ball.type = ShapePart::Type::kSphere;
  ball.radius = 0.05;
  ball.position = {-0.2, 0, 0};
  ShapePart rod;
  rod.type = ShapePart::Type::kCapsule;
  rod.radius = 0.01;
  rod.half_length = 0.2;
  rod.orientation = {std::sqrt(0.5), 0, std::sqrt(0.5), 0};  // along x
  ShapePart other = ball;
  other.position = {0.2, 0, 0};
  BodyOptions options;
  options.position = {1, 2, 3};
  options.mass = 2.0;
  options.center_of_mass = Eigen::Vector3d(0.05, 0, 0);
  Eigen::Matrix3d inertia;
  inertia << 0.001, 0.0001, 0, 0.0001, 0.04, 0, 0, 0, 0.04;
  options.inertia = inertia;
  const Result<int64_t> added = client_->AddCompound({ball, rod, other}, options);
  ASSERT_TRUE(added.ok()) << added.status;
  const CommandResult step = client_->Step(1);
  ASSERT_TRUE(step.ok()) << step;
  const std::optional<state_t> state = client_->LatestState();
  ASSERT_TRUE(state.has_value());
  ASSERT_EQ(state->bodies.size(), 1u);
  EXPECT_NEAR(state->bodies[0].position[0], 1.05, 1e-12);

  ShapePart plane;
  plane.type = static_cast<ShapePart::Type>(3);  // PLANE on the wire
  const Result<int64_t> refused = client_->AddCompound({ball, plane});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status.message.find("parts[1].type must be sphere, box, capsule or convex, got plane"),
            std::string::npos)
      << refused.status;
}

}  // namespace
}  // namespace contactsim::testing
