// Collision filters on the real server through the C++ client: a filter
// given at ADD (BodyOptions::filter), one changed by SetFilter, a joint's
// collide_connected, and SetFilter's refusal of an unknown body.
#include <optional>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using FilterTest = ServerTest;

constexpr double kHalf = 0.1;  // m, the boxes

std::optional<double> Height(Client& client, int64_t id) {
  const std::optional<state_t> state = client.LatestState();
  if (!state) return std::nullopt;
  for (const body_state_t& b : state->bodies) {
    if (b.id == id) return b.position[2];
  }
  return std::nullopt;
}

// Verifies that a box whose mask excludes the lower box's category falls
// through it after SetFilter, having rested on it before; and that
// SetFilter on an unknown id is NOT_FOUND.
TEST_F(FilterTest, SetFilterDropsTheTopBoxThroughTheLowerOne) {
  BodyOptions ground;
  ASSERT_TRUE(client_->AddPlane(Eigen::Vector3d::UnitZ(), 0.0, ground).ok());
  BodyOptions lower;
  lower.position = {0.0, 0.0, kHalf + 1e-3};
  lower.restitution = 0.0;
  lower.filter = CollisionFilter{2u, 0xFFFFFFFFu, 0};
  ASSERT_TRUE(client_->AddBox(Eigen::Vector3d::Constant(kHalf), lower).ok());
  BodyOptions upper = lower;
  upper.position = {0.0, 0.0, 3 * kHalf + 2e-3};
  upper.filter.reset();
  const Result<int64_t> top = client_->AddBox(Eigen::Vector3d::Constant(kHalf), upper);
  ASSERT_TRUE(top.ok()) << top.status;
  ASSERT_TRUE(client_->Step(240).ok());
  ASSERT_NEAR(Height(*client_, top.value).value_or(-1.0), 3 * kHalf, 0.01);
  const CommandResult set = client_->SetFilter(top.value, CollisionFilter{1u, 1u, 0});
  ASSERT_TRUE(set.ok()) << set;
  ASSERT_TRUE(client_->Step(240).ok());
  EXPECT_NEAR(Height(*client_, top.value).value_or(-1.0), kHalf, 0.01);
  const CommandResult missing = client_->SetFilter(999999, CollisionFilter{});
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.code, ReplyCode::kNotFound);
}

// Verifies that a joint added with collide_connected is accepted.
TEST_F(FilterTest, JointWithCollideConnectedIsAdded) {
  BodyOptions a, b;
  a.position = {0.0, 0.0, 1.0};
  b.position = {0.0, 0.0, 1.2};
  const Result<int64_t> ia = client_->AddSphere(0.1, a), ib = client_->AddSphere(0.1, b);
  ASSERT_TRUE(ia.ok() && ib.ok());
  JointOptions options;
  options.collide_connected = true;
  const Result<int64_t> joint = client_->AddJoint(JointType::kBall, ia.value, ib.value, {0.0, 0.0, 1.1}, options);
  EXPECT_TRUE(joint.ok()) << joint.status;
}

}  // namespace
}  // namespace contactsim::testing
