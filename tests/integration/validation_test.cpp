// Bad input against the real server: every rejected command gets an error
// reply naming the field, and leaves the world exactly as it was.
//
// "Exactly as it was" is checked against a twin: two servers build the same
// world, only one receives the bad command, then both take the same steps.
// Their STATEs (state_hash and every body, bit for bit) must still agree;
// a paused server publishes no STATE without stepping, so a twin is the
// only witness that needs no server internals.
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kStepsBefore = 3;  // steps taken before the bad command
constexpr int kStepsAfter = 2;   // steps that would expose any change

void ExpectSameBody(const body_state_t& a, const body_state_t& b) {
  EXPECT_EQ(a.id, b.id);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.position[i], b.position[i]) << "body " << a.id << " position " << i;
    EXPECT_EQ(a.linear_velocity[i], b.linear_velocity[i]) << "body " << a.id;
    EXPECT_EQ(a.angular_velocity[i], b.angular_velocity[i]) << "body " << a.id;
  }
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(a.orientation[i], b.orientation[i]) << "body " << a.id;
  }
}

void ExpectSameWorld(const state_t& a, const state_t& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.state_hash, b.state_hash);
  ASSERT_EQ(a.num_bodies, b.num_bodies);
  for (int i = 0; i < a.num_bodies; ++i) ExpectSameBody(a.bodies[i], b.bodies[i]);
}

class ValidationTest : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    if (HasFatalFailure()) return;
    StartServer(twin_, twin_client_);
    if (HasFatalFailure()) return;
    BuildWorld(*client_, &ball_id_);
    int64_t twin_ball_id = 0;
    BuildWorld(*twin_client_, &twin_ball_id);
    if (HasFatalFailure()) return;
    ExpectSameWorld(*client_->LatestState(), *twin_client_->LatestState());
  }

  void TearDown() override {
    StopServer(twin_, twin_client_);
    ServerTest::TearDown();
  }

  // A plane, a falling sphere and a tumbling box, a few steps in.
  static void BuildWorld(Client& client, int64_t* ball_id) {
    ASSERT_TRUE(client.AddPlane(Eigen::Vector3d::UnitZ()).ok());
    BodyOptions ball;
    ball.position = {0.0, 0.0, 0.5};
    ball.velocity = {0.3, 0.0, 0.0};
    const Result<int64_t> added = client.AddSphere(0.1, ball);
    ASSERT_TRUE(added.ok()) << added.status;
    *ball_id = added.value;
    BodyOptions box;
    box.position = {1.0, 0.0, 1.0};
    box.angular_velocity = {0.0, 1.0, 2.0};
    box.mass = 2.0;
    ASSERT_TRUE(client.AddBox({0.2, 0.1, 0.05}, box).ok());
    const CommandResult step = client.Step(kStepsBefore);
    ASSERT_TRUE(step.ok()) << step;
  }

  // Both servers step on; the one that rejected a command must match the
  // twin that never saw it.
  void ExpectWorldUnchanged() {
    const CommandResult step = client_->Step(kStepsAfter);
    const CommandResult twin_step = twin_client_->Step(kStepsAfter);
    ASSERT_TRUE(step.ok()) << step;
    ASSERT_TRUE(twin_step.ok()) << twin_step;
    ExpectSameWorld(*client_->LatestState(), *twin_client_->LatestState());
  }

  static void ExpectRejected(const CommandResult& result, ReplyCode code,
                             const std::string& named) {
    EXPECT_EQ(ReplyCodeName(result.code), ReplyCodeName(code)) << result;
    EXPECT_NE(result.message.find(named), std::string::npos)
        << "the message should name \"" << named << "\": " << result.message;
    EXPECT_TRUE(result.ids.empty()) << result;
  }

  ServerProcess twin_;
  std::unique_ptr<Client> twin_client_;
  int64_t ball_id_ = 0;  // the sphere of BuildWorld on the tested server
};

// Verifies a NaN in a new body's position is rejected naming "position".
TEST_F(ValidationTest, NanPositionIsRejected) {
  BodyOptions options;
  options.position = {0.0, kNaN, 1.0};
  ExpectRejected(client_->AddSphere(0.1, options).status,
                 ReplyCode::kInvalidArgument, "position");
  ExpectWorldUnchanged();
}

// Verifies a zero and a negative sphere radius are rejected naming "radius".
TEST_F(ValidationTest, NonPositiveRadiusIsRejected) {
  ExpectRejected(client_->AddSphere(0.0).status, ReplyCode::kInvalidArgument,
                 "radius");
  ExpectRejected(client_->AddSphere(-1.0).status, ReplyCode::kInvalidArgument,
                 "radius");
  ExpectWorldUnchanged();
}

// Verifies a negative mass, on ADD and on SET_MASS, is rejected naming "mass".
TEST_F(ValidationTest, NegativeMassIsRejected) {
  BodyOptions options;
  options.mass = -1.0;
  ExpectRejected(client_->AddSphere(0.1, options).status,
                 ReplyCode::kInvalidArgument, "mass");
  ExpectRejected(client_->SetMass(ball_id_, -1.0), ReplyCode::kInvalidArgument,
                 "mass");
  ExpectWorldUnchanged();
}

// Verifies commands on an unknown body id are rejected naming the id.
TEST_F(ValidationTest, UnknownBodyIdIsRejected) {
  constexpr int64_t kUnknown = 4242;
  ExpectRejected(client_->SetPose(kUnknown, {0.0, 0.0, 1.0}),
                 ReplyCode::kNotFound, "4242");
  ExpectRejected(client_->RemoveBody(kUnknown), ReplyCode::kNotFound, "4242");
  ExpectRejected(client_->ApplyImpulse(kUnknown, {0.0, 0.0, 1.0}),
                 ReplyCode::kNotFound, "4242");
  ExpectWorldUnchanged();
}

// Verifies switching to an unregistered contact method is rejected naming it.
TEST_F(ValidationTest, UnknownContactMethodIsRejected) {
  ExpectRejected(client_->SetContactMethod("no_such_method"),
                 ReplyCode::kNotFound, "no_such_method");
  ExpectWorldUnchanged();
}

// Verifies undecodable payloads on BODY_CMD (garbage, and a valid message cut
// short) each get a DECODE_ERROR reply with request id -1 and no client id.
TEST_F(ValidationTest, UndecodablePayloadGetsDecodeError) {
  std::mutex mutex;
  std::vector<reply_t> replies;
  // Runs on the client's LCM thread; removed before `replies` goes away.
  const int callback = client_->OnReply([&](const reply_t& reply) {
    std::lock_guard<std::mutex> lock(mutex);
    if (reply.request_id == -1) replies.push_back(reply);
  });

  lcm::LCM raw(server_.url());
  ASSERT_TRUE(raw.good());
  const std::string channel = server_.prefix() + "_BODY_CMD";
  const std::string garbage = "this is not an LCM message \x01\x02\x03\xff";
  ASSERT_EQ(raw.publish(channel, garbage.data(), static_cast<int>(garbage.size())), 0);
  body_cmd_t command{};
  command.client_id = "truncated";
  command.request_id = 7;
  command.op = body_cmd_t::REMOVE;
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  ASSERT_EQ(raw.publish(channel, buffer.data(), static_cast<int>(buffer.size() / 2)), 0);

  const auto deadline = std::chrono::steady_clock::now() + kReplyTimeout;
  while (std::chrono::steady_clock::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (replies.size() >= 2) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  client_->RemoveCallback(callback);
  std::vector<reply_t> received;
  {
    std::lock_guard<std::mutex> lock(mutex);
    received = replies;
  }
  ASSERT_EQ(received.size(), 2u) << "expected one DECODE_ERROR reply per payload";
  for (const reply_t& reply : received) {
    EXPECT_EQ(reply.code, reply_t::DECODE_ERROR) << reply.message;
    EXPECT_EQ(reply.client_id, "");
    EXPECT_EQ(reply.num_ids, 0);
    EXPECT_FALSE(reply.message.empty());
  }
  ExpectWorldUnchanged();
}

}  // namespace
}  // namespace contactsim::testing
