#include "bench/tools/lockstep_bench/arm_lockstep.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "bench/tools/lockstep_bench/process_cpu.h"
#include "contactsim/controller.h"

namespace contactsim::bench {

ArmLockstepResult MeasureArmLockstep(Client& client, const std::string& urdf, double seconds, pid_t server) {
  ArmLockstepResult r;
  auto fail = [&](const char* what, const CommandResult& c) {
    r.error = std::string(what) + ": " + ToString(c);
    return r;
  };
  CommandResult c;
  if (!(c = client.Pause()).ok() || !(c = client.Reset()).ok()) return fail("reset", c);
  if (!(c = client.SetTimestep(1e-3)).ok()) return fail("timestep", c);
  ModelOptions options;
  options.fixed_base = true;
  const Result<Model> arm = client.LoadModel(urdf, options);
  if (!arm.ok()) return fail("load model", arm.status);
  JointCommand gains;
  gains.model_id = arm.value.id;
  if (!(c = client.Step(10)).ok()) return fail("step", c);
  const auto joints = client.LatestJointState();
  r.joints = joints ? joints->num_joints : 0;
  gains.kp.assign(r.joints, 2e4);
  gains.kd.assign(r.joints, 400.0);
  if (!(c = client.SetJointActuators(gains)).ok()) return fail("gains", c);
  const auto state = client.LatestState();
  const int joint_state_bytes = joints ? joints->getEncodedSize() : 0;
  JointCommand targets;
  targets.model_id = arm.value.id;
  targets.target_position.assign(r.joints, 0.0);
  input_t in{};
  in.client_id = client.client_id();
  in.joints = EncodeJointCommand(targets);
  r.input_bytes = in.getEncodedSize();

  const int n = r.joints;
  const int64_t model = arm.value.id;
  // JOINT_STATEs heard while in lockstep: the server's joint_state option decides
  std::atomic<int64_t> joint_states{0};
  const int counter = client.OnJointState([&joint_states](const joint_state_t&) { ++joint_states; });
  Controller controller(client, [n, model](const state_t& s, const joint_state_t&) {
    ControlOutput out;
    out.joints.model_id = model;
    out.joints.target_position.assign(n, 0.2 * std::sin(2.0 * M_PI * s.time));
    return out;
  });
  if (!(c = controller.Start(LatePolicy::kWait)).ok()) return fail("register controller", c);
  if (!(c = client.SetMode(Mode::kLockstep)).ok() || !(c = client.Resume()).ok()) return fail("lockstep", c);
  const int64_t warm = (state ? state->step : 0) + 50;
  if (!controller.WaitForStep(warm, std::chrono::seconds(30))) {
    r.error = "lockstep did not reach step " + std::to_string(warm);
    return r;
  }
  const ProcessSched sched0 = ReadProcessSched(server) + ReadProcessSched(getpid());
  const int64_t js0 = joint_states.load();
  const int64_t s0 = controller.answered();
  const auto t0 = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const int64_t s1 = controller.answered();
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ProcessSched spent = ReadProcessSched(server) + ReadProcessSched(getpid()) - sched0;
  const int64_t js1 = joint_states.load();
  r.cycles_per_second = (s1 - s0) / elapsed;
  r.cpu_per_cycle = s1 > s0 ? spent.cpu_seconds / (s1 - s0) : 0.0;
  r.runs_per_cycle = s1 > s0 ? spent.runs / (s1 - s0) : 0.0;
  r.joint_states_per_cycle = s1 > s0 ? static_cast<double>(js1 - js0) / (s1 - s0) : 0.0;
  const auto last = client.LatestState();
  r.state_bytes = (last ? last->getEncodedSize() : 0) + (r.joint_states_per_cycle > 0.5 ? joint_state_bytes : 0);
  client.RemoveCallback(counter);
  client.Pause();
  controller.Stop();
  client.SetMode(Mode::kFreeRun);
  return r;
}

}  // namespace contactsim::bench
