#include "contactsim/controller.h"

namespace contactsim {

Controller::Controller(Client& client, Policy policy) : client_(client), policy_(std::move(policy)) {}
Controller::Controller(Client& client, JointPolicy policy) : client_(client), joint_policy_(std::move(policy)) {}

Controller::~Controller() {
  if (callback_id_ >= 0) client_.RemoveCallback(callback_id_);
  if (registered_) client_.ReleaseController();
}

CommandResult Controller::Start(LatePolicy late, double late_timeout) {
  // listen first: the server republishes the current STATE on registration
  if (callback_id_ < 0) callback_id_ = client_.OnState([this](const state_t& s) { OnState(s); });
  CommandResult result = client_.RegisterController(late, late_timeout);
  registered_ = result.ok();  // from here on STATEs are answered
  return result;
}

CommandResult Controller::Stop() {
  if (callback_id_ >= 0) client_.RemoveCallback(callback_id_);
  callback_id_ = -1;
  registered_ = false;
  return client_.ReleaseController();
}

// A STATE before the registration is acknowledged is not answered (its
// input could reach the server first and be refused); a STATE published
// again while the server waits is answered by resending the same input,
// which recovers an input lost on UDP or refused that way.
void Controller::OnState(const state_t& state) {
  if (!registered_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (state.step < answered_) return;
    if (state.step == answered_) {
      client_.SendInput(state.step + 1, last_inputs_.bodies, last_inputs_.joints, last_request_id_);
      return;
    }
  }
  ControlOutput inputs;
  if (joint_policy_) {
    // STATE carries the step's joints: one message a step, nothing to wait for
    inputs = joint_policy_(state, client_.JointStateOf(state));
  } else {
    inputs.bodies = policy_(state);
  }
  const int64_t id = client_.SendInput(state.step + 1, inputs.bodies, inputs.joints);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    answered_ = state.step;
    last_inputs_ = std::move(inputs);
    last_request_id_ = id;
  }
  answered_cv_.notify_all();
}

bool Controller::WaitForStep(int64_t step, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return answered_cv_.wait_for(lock, timeout, [&] { return answered_ >= step; });
}

int64_t Controller::answered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return answered_;
}

}  // namespace contactsim
