#include "contactsim/controller.h"

namespace contactsim {

Controller::Controller(Client& client, Policy policy) : client_(client), policy_(std::move(policy)) {}

Controller::~Controller() {
  if (callback_id_ >= 0) client_.RemoveCallback(callback_id_);
  if (registered_) client_.ReleaseController();
}

CommandResult Controller::Start(LatePolicy late, double late_timeout) {
  // listen first: the server republishes the current STATE on registration
  if (callback_id_ < 0) callback_id_ = client_.OnState([this](const state_t& s) { OnState(s); });
  CommandResult result = client_.RegisterController(late, late_timeout);
  registered_ = result.ok();
  return result;
}

CommandResult Controller::Stop() {
  if (callback_id_ >= 0) client_.RemoveCallback(callback_id_);
  callback_id_ = -1;
  registered_ = false;
  return client_.ReleaseController();
}

void Controller::OnState(const state_t& state) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (state.step <= answered_) return;  // a STATE published again
  }
  client_.SendInput(state.step + 1, policy_(state));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    answered_ = state.step;
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
