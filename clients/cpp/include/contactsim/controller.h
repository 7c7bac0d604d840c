// contactsim::Controller: runs a callback state -> inputs in lockstep
// (docs/lockstep.md). Each STATE k-1 is answered with the input for step k
// from the client's receive thread, so a step costs one STATE and one input
// on the wire. The callback runs on that thread: it must be quick and must
// not call the blocking commands of the same Client.
//
//   contactsim::Controller ctl(client, [&](const state_t& s) { return Pd(s); });
//   ctl.Start();                               // registers
//   client.SetMode(contactsim::Mode::kLockstep);
//   client.Resume();
//   ctl.WaitForStep(720, std::chrono::seconds(30));
//   ctl.Stop();                                // releases
//
// A JointPolicy also reads the step's joints, from STATE's joint block
// (Client::JointStateOf: one message a step), and may command joints for
// that one step:
//   contactsim::Controller ctl(client, [&](const state_t& s, const joint_state_t& j) {
//     contactsim::ControlOutput out;
//     out.joints.model_id = arm.id;
//     out.joints.torque = Pd(j);
//     return out;
//   });
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

#include "contactsim/client.h"

namespace contactsim {

// One step's input: wrenches on bodies and joint commands.
struct ControlOutput {
  BodyInputs bodies;
  JointCommand joints;
};

class Controller {
 public:
  using Policy = std::function<BodyInputs(const state_t&)>;
  using JointPolicy = std::function<ControlOutput(const state_t&, const joint_state_t&)>;

  Controller(Client& client, Policy policy);
  Controller(Client& client, JointPolicy policy);
  ~Controller();  // stops listening (and releases, if still registered)
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  CommandResult Start(LatePolicy late = LatePolicy::kDefault, double late_timeout = 0.0);
  CommandResult Stop();
  // True once the STATE of `step` has been answered, false after `timeout`.
  bool WaitForStep(int64_t step, std::chrono::milliseconds timeout);
  int64_t answered() const;  // step of the last STATE answered, -1 before any

 private:
  void OnState(const state_t& state);

  Client& client_;
  Policy policy_;
  JointPolicy joint_policy_;  // set instead of policy_
  int callback_id_ = -1;
  std::atomic<bool> registered_{false};
  mutable std::mutex mutex_;
  std::condition_variable answered_cv_;
  int64_t answered_ = -1;
  ControlOutput last_inputs_;   // the input that answered `answered_`
  int64_t last_request_id_ = 0;
};

}  // namespace contactsim
