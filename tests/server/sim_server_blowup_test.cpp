// A world that blows up under the server: the step's state is not
// published, the running STEP is answered with the reason, STATUS carries
// it, and stepping is refused until a command replaces the world.
#include <gtest/gtest.h>

#include <contactsim/state_t.hpp>
#include <contactsim/status_t.hpp>

#include <cmath>
#include <memory>

#include "tests/server/sim_server_fixture.h"

namespace contactsim {
namespace {

using testing::Encode;
using testing::RecordingTransport;

// The impulse method, made to diverge from step `from` on: every step
// multiplies each dynamic body's momentum by 10, as an unstable solver does
// geometrically.
class DivergingMethod : public ContactMethod {
 public:
  explicit DivergingMethod(int64_t from) : from_(from) { EXPECT_TRUE(CreateContactMethod("impulse", &inner_).ok()); }
  const char* Name() const override { return inner_->Name(); }
  ContactValueKind ValueKind() const override { return inner_->ValueKind(); }
  Status SetParams(const ParamMap& params) override { return inner_->SetParams(params); }
  ParamMap Params() const override { return inner_->Params(); }
  std::vector<ParamDoc> ParamDocs() const override { return inner_->ParamDocs(); }
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override {
    const StepStats stats = inner_->Step(world, detector, contacts);
    if (world.step >= from_) {
      for (RigidBody& b : world.bodies()) b.P *= 10.0;
    }
    return stats;
  }

 private:
  int64_t from_;
  std::unique_ptr<ContactMethod> inner_;
};

class SimServerBlowUpTest : public ::testing::Test {
 protected:
  SimServerBlowUpTest() : server_(testing::TestServerOptions(), &transport_) {}
  void Start(int64_t diverge_from) {
    ASSERT_TRUE(server_.Init(nullptr, std::make_shared<DivergingMethod>(diverge_from)).ok());
  }
  reply_t SendScene(scene_cmd_t m) {
    m.client_id = "test";
    m.request_id = ++request_id_;
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel("SCENE_CMD"), bytes.data(), static_cast<int>(bytes.size()));
    while (server_.Tick()) {
    }
    return transport_.All<reply_t>("T_REPLY").back();
  }
  reply_t Step(int steps) {
    scene_cmd_t m{};
    m.op = scene_cmd_t::STEP;
    m.steps = steps;
    return SendScene(m);
  }
  void AddBall() {
    body_cmd_t m{};
    m.client_id = "test";
    m.request_id = ++request_id_;
    m.op = body_cmd_t::ADD;
    m.shape = body_cmd_t::SPHERE;
    m.radius = 0.1;
    m.position[2] = 1.0;
    m.linear_velocity[0] = 1.0;
    m.orientation[0] = 1.0;
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel("BODY_CMD"), bytes.data(), static_cast<int>(bytes.size()));
    server_.Tick();
    ASSERT_EQ(transport_.All<reply_t>("T_REPLY").back().code, reply_t::OK);
  }

  RecordingTransport transport_;
  SimServer server_;
  int64_t request_id_ = 0;
};

// Verifies that a STEP through a blow-up is answered FAILED_PRECONDITION
// naming the step, that no STATE of a blown-up step is published, that
// STATUS reports the fault at once, and that STEP and RESUME are refused
// (the world untouched) until RESET, after which stepping works again.
TEST_F(SimServerBlowUpTest, ABlowUpStopsSteppingUntilTheWorldIsReplaced) {
  Start(/*diverge_from=*/5);
  AddBall();
  const reply_t r = Step(100);
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION) << r.message;
  EXPECT_NE(r.message.find("blew up at step"), std::string::npos) << r.message;
  const int64_t stopped = server_.world().step;
  EXPECT_GT(stopped, 5);
  EXPECT_LT(stopped, 100);
  for (const state_t& s : transport_.All<state_t>("T_STATE")) {
    EXPECT_LT(s.step, stopped) << "the blown-up step's state was published";
    for (int i = 0; i < s.num_bodies; ++i) {
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(s.bodies[i].linear_velocity[k]));
    }
  }
  const status_t status = transport_.All<status_t>("T_STATUS").back();
  EXPECT_NE(status.fault.find("blew up at step " + std::to_string(stopped)), std::string::npos) << status.fault;
  EXPECT_TRUE(status.paused);

  const uint64_t hash = HashWorldState(server_.world());
  for (int8_t op : {scene_cmd_t::STEP, scene_cmd_t::RESUME}) {
    scene_cmd_t m{};
    m.op = op;
    m.steps = 1;
    const reply_t refused = SendScene(m);
    EXPECT_EQ(refused.code, reply_t::FAILED_PRECONDITION) << refused.message;
    EXPECT_NE(refused.message.find("RESET"), std::string::npos) << refused.message;
  }
  EXPECT_EQ(HashWorldState(server_.world()), hash);

  scene_cmd_t reset{};
  reset.op = scene_cmd_t::RESET;
  ASSERT_EQ(SendScene(reset).code, reply_t::OK);
  const reply_t again = Step(3);
  EXPECT_EQ(again.code, reply_t::OK) << again.message;
  EXPECT_EQ(server_.world().step, 3);
}

// Verifies that a sound run (a ball thrown and falling freely for 10 s, to
// 98 m/s) never trips the watch.
TEST_F(SimServerBlowUpTest, ASoundRunNeverTripsIt) {
  Start(/*diverge_from=*/1000000);
  AddBall();
  const reply_t r = Step(2400);
  EXPECT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(transport_.All<status_t>("T_STATUS").back().fault, "");
}

}  // namespace
}  // namespace contactsim
