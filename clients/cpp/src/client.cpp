// Transport half of contactsim::Client: the LCM receive thread, reply
// matching and the latest STATE / CONTACTS / STATUS. The command builders
// live in client_commands.cpp.
#include "contactsim/client.h"

#include "contactsim/protocol.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

#include <lcm/lcm-cpp.hpp>

#include "client_auth.h"

namespace contactsim {
namespace {

// How long one handleTimeout call may block; bounds how late the destructor
// notices that it should stop.
constexpr int kPollMillis = 50;

// Two Clients in one process must not share a client id: both would see the
// other's replies with the same request ids. Only the first gets the plain
// "cpp-<pid>" name.
std::string DefaultClientId() {
  static std::atomic<int> instances{0};
  const int n = instances.fetch_add(1);
  std::string id = "cpp-" + std::to_string(::getpid());
  return n == 0 ? id : id + "-" + std::to_string(n);
}

template <typename T>
std::vector<std::function<void(const T&)>> Snapshot(
    std::mutex& mutex,
    const std::map<int, std::function<void(const T&)>>& callbacks) {
  std::lock_guard<std::mutex> lock(mutex);
  std::vector<std::function<void(const T&)>> out;
  out.reserve(callbacks.size());
  for (const auto& [id, callback] : callbacks) out.push_back(callback);
  return out;
}

}  // namespace

struct Client::Callbacks {
  int next_id = 1;
  std::map<int, StateCallback> state;
  std::map<int, ContactsCallback> contacts;
  std::map<int, StatusCallback> status;
  std::map<int, ReplyCallback> reply;
  std::map<int, SensorsCallback> sensors;
  std::map<int, JointStateCallback> joint_state;
};

std::string ResolveLcmUrl(const std::string& url) {
  if (!url.empty()) return url;
  // LCM itself would fall back to a URL without recv_buf_size, so resolve
  // the project default here.
  const char* env = std::getenv("LCM_DEFAULT_URL");
  if (env != nullptr && env[0] != '\0') return env;
  return kDefaultLcmUrl;
}

// Raw subscriptions, so that a signature is checked before any decoder
// reads the bytes.
template <typename Msg>
bool Client::Unwrap(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Msg* msg) {
  const int size = static_cast<int>(rbuf->data_size);
  const int payload = auth_ ? auth_->Unwrap(channel, rbuf->data, size) : UnsignedSize(rbuf->data, size);
  return payload >= 0 && msg->decode(rbuf->data, 0, payload) >= 0;
}

void Client::OnReply(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  reply_t m;
  if (c->Unwrap(rb, ch, &m)) c->HandleReply(rb, ch, &m);
}
void Client::OnState(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  state_t m;
  if (c->Unwrap(rb, ch, &m)) c->HandleState(rb, ch, &m);
}
void Client::OnContacts(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  contacts_t m;
  if (c->Unwrap(rb, ch, &m)) c->HandleContacts(rb, ch, &m);
}
void Client::OnStatus(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  status_t m;
  if (c->Unwrap(rb, ch, &m)) c->HandleStatus(rb, ch, &m);
}
// MODEL_INFO (client_models.cpp): kept for LoadModel and Models
void Client::OnModelInfo(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  model_info_t m;
  if (!c->Unwrap(rb, ch, &m)) return;
  std::lock_guard<std::mutex> lock(c->mutex_);
  c->latest_model_info_ = std::move(m);
  ++c->model_infos_received_;
  c->changed_.notify_all();
}

void Client::OnProgress(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  progress_t m;
  if (c->Unwrap(rb, ch, &m)) c->HandleProgress(&m);
}

void Client::OnRayHits(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  ray_hits_t m;
  if (!c->Unwrap(rb, ch, &m) || m.client_id != c->options_.client_id) return;
  std::lock_guard<std::mutex> lock(c->mutex_);
  c->ray_hits_[m.request_id] = std::move(m);
  // answers nobody took (their RayCast gave up): the oldest go
  while (c->ray_hits_.size() > 64) c->ray_hits_.erase(c->ray_hits_.begin());
  c->changed_.notify_all();
}

void Client::OnSensors(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  sensors_t m;
  if (!c->Unwrap(rb, ch, &m)) return;
  for (const auto& callback : Snapshot(c->mutex_, c->callbacks_->sensors)) callback(m);
  std::lock_guard<std::mutex> lock(c->mutex_);
  c->latest_sensors_ = std::move(m);
}

void Client::OnJointState(const lcm::ReceiveBuffer* rb, const std::string& ch, Client* c) {
  joint_state_t m;
  if (!c->Unwrap(rb, ch, &m)) return;
  for (const auto& callback : Snapshot(c->mutex_, c->callbacks_->joint_state)) callback(m);
  std::lock_guard<std::mutex> lock(c->mutex_);
  c->latest_joint_state_ = std::move(m);
  c->changed_.notify_all();
}

void Client::SubscribeSensors(int queue_capacity) {
  lcm_->subscribeFunction(Channel(protocol::kRayHits), &OnRayHits, this)->setQueueCapacity(queue_capacity);
  lcm_->subscribeFunction(Channel(protocol::kSensors), &OnSensors, this)->setQueueCapacity(queue_capacity);
  lcm_->subscribeFunction(Channel(protocol::kJointState), &OnJointState, this)->setQueueCapacity(queue_capacity);
}

int Client::OnJointState(JointStateCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->joint_state[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

std::optional<joint_state_t> Client::LatestJointState() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return LatestJointStateLocked();
}

std::optional<joint_state_t> Client::LatestJointStateLocked() const {
  // of one step, JOINT_STATE: it names the joints without MODEL_INFO
  const bool state_newer = latest_state_ && latest_state_->num_joints > 0 &&
                           (!latest_joint_state_ || latest_joint_state_->step < latest_state_->step);
  if (state_newer) return JointStateOfLocked(*latest_state_);
  return latest_joint_state_;
}

joint_state_t Client::JointStateOf(const state_t& state) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return JointStateOfLocked(state);
}

joint_state_t Client::JointStateOfLocked(const state_t& state) const {
  joint_state_t m;
  m.time = state.time;
  m.step = state.step;
  m.num_joints = state.num_joints;
  m.joint_ids = state.joint_ids;
  m.model_ids = state.joint_model_ids;
  m.positions = state.joint_positions;
  m.velocities = state.joint_velocities;
  m.efforts = state.joint_efforts;
  m.names.resize(state.joint_ids.size());
  for (size_t i = 0; i < state.joint_ids.size(); ++i) {
    const std::string* name = nullptr;
    if (latest_model_info_ && state.joint_model_ids[i] != 0) {
      for (const model_entry_t& e : latest_model_info_->models) {
        if (e.model_id != state.joint_model_ids[i]) continue;
        for (size_t k = 0; k < e.joint_ids.size() && name == nullptr; ++k) {
          if (e.joint_ids[k] == state.joint_ids[i]) name = &e.joint_names[k];
        }
      }
    }
    m.names[i] = name != nullptr ? *name : std::to_string(state.joint_ids[i]);
  }
  return m;
}

std::optional<joint_state_t> Client::WaitForJointState(const std::function<bool(const joint_state_t&)>& predicate,
                                                       std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  std::optional<joint_state_t> found;
  const bool ok = changed_.wait_for(lock, timeout, [&] {
    found = LatestJointStateLocked();
    return found && predicate(*found);
  });
  if (!ok) return std::nullopt;
  return found;
}

int Client::OnSensors(SensorsCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->sensors[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

std::optional<sensors_t> Client::LatestSensors() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_sensors_;
}

Client::Client(ClientOptions options)
    : options_(std::move(options)), callbacks_(std::make_unique<Callbacks>()) {
  options_.url = ResolveLcmUrl(options_.url);
  if (options_.client_id.empty()) options_.client_id = DefaultClientId();
  const std::string key_file = options_.auth_key_file ? *options_.auth_key_file : ResolveAuthKeyFile("");
  if (!key_file.empty()) {
    std::string key;
    if (!LoadAuthKey(key_file, &key, &error_)) return;  // never opens LCM: nothing unsigned goes out
    auth_ = std::make_unique<ClientAuth>(std::move(key), options_.auth_window_s);
  }
  lcm_ = std::make_unique<lcm::LCM>(options_.url);
  if (!lcm_->good()) return;
  // LCM drops messages beyond 30 queued per subscription by default; a
  // free-running server sends STATE in far larger bursts.
  constexpr int kQueueCapacity = 100000;
  // Plain-function trampolines rather than LCM's pointer-to-member
  // subscriptions, whose dispatch UBSan flags inside lcm-cpp-impl.hpp.
  lcm_->subscribeFunction(Channel(protocol::kReply), &OnReply, this)->setQueueCapacity(kQueueCapacity);
  lcm_->subscribeFunction(Channel(protocol::kState), &OnState, this)->setQueueCapacity(kQueueCapacity);
  lcm_->subscribeFunction(Channel(protocol::kContacts), &OnContacts, this)->setQueueCapacity(kQueueCapacity);
  lcm_->subscribeFunction(Channel(protocol::kStatus), &OnStatus, this)->setQueueCapacity(kQueueCapacity);
  lcm_->subscribeFunction(Channel(protocol::kProgress), &OnProgress, this)->setQueueCapacity(kQueueCapacity);
  SubscribeSensors(kQueueCapacity);
  lcm_->subscribeFunction(Channel(protocol::kModelInfo), &OnModelInfo, this)->setQueueCapacity(kQueueCapacity);
  thread_ = std::thread(&Client::Run, this);
}

Client::~Client() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

bool Client::good() const { return error_.empty() && lcm_ && lcm_->good(); }

std::string Client::error() const {
  if (!error_.empty()) return error_;
  return good() ? "" : "LCM is not usable with url " + options_.url;
}

uint64_t Client::auth_failures() const { return auth_ ? auth_->failures() : 0; }

std::string Client::last_auth_failure() const { return auth_ ? auth_->last_failure() : ""; }

std::string Client::Channel(const std::string& suffix) const {
  return options_.prefix + "_" + suffix;
}

void Client::Run() {
  while (running_) lcm_->handleTimeout(kPollMillis);
}

int64_t Client::NextRequestId() {
  std::lock_guard<std::mutex> lock(mutex_);
  return ++last_request_id_;
}

bool Client::Transmit(const std::string& channel, const void* data, int size) {
  if (!auth_) return lcm_->publish(channel, data, size) == 0;
  const std::string signed_message = auth_->Sign(channel, data, size);
  return lcm_->publish(channel, signed_message.data(), static_cast<unsigned>(signed_message.size())) == 0;
}

bool Client::PublishRaw(const std::string& channel, const void* data, int size) {
  return good() && Transmit(channel, data, size);
}

CommandResult Client::Publish(const std::string& channel, int64_t request_id,
                              const void* data, int size) {
  CommandResult result;
  result.request_id = request_id;
  if (!good()) {
    result.code = ReplyCode::kTransport;
    result.message = error();
    return result;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  // Registered before publishing: the reply, or the first progress report
  // (sent as soon as the server accepts a STEP), may arrive before publish
  // returns.
  pending_[request_id] = std::nullopt;
  heard_[request_id] = Clock::now();
  lock.unlock();
  if (!Transmit(channel, data, size)) {
    lock.lock();
    pending_.erase(request_id);
    heard_.erase(request_id);
    result.code = ReplyCode::kTransport;
    result.message = "LCM publish on " + channel + " failed";
    return result;
  }
  lock.lock();
  // as long as the server reports progress on it (HandleProgress), counted
  // from the end of the publish
  heard_[request_id] = std::max(heard_[request_id], Clock::now());
  while (!pending_[request_id].has_value()) {
    const Clock::time_point silent_until = heard_[request_id] + options_.reply_timeout;
    if (Clock::now() >= silent_until) break;
    changed_.wait_until(lock, silent_until);
  }
  const bool replied = pending_[request_id].has_value();
  std::optional<reply_t> reply = std::move(pending_[request_id]);
  pending_.erase(request_id);
  heard_.erase(request_id);
  progress_callbacks_.erase(request_id);
  // a progress callback still running may use what its caller owns
  changed_.wait(lock, [&] { return progress_in_flight_ == 0; });
  if (!replied) {
    result.code = ReplyCode::kTimeout;
    result.message = "no reply to request " + std::to_string(request_id) +
                     " on " + Channel(protocol::kReply) + " and no progress for " +
                     std::to_string(options_.reply_timeout.count()) + " ms";
    if (auth_ && auth_->failures() > 0) {  // the likely cause: a server with another key, or none
      result.message += " (" + std::to_string(auth_->failures()) +
                        " server messages failed their signature check, the last: " + auth_->last_failure() + ")";
    }
    return result;
  }
  result.code = static_cast<ReplyCode>(reply->code);
  result.message = std::move(reply->message);
  result.step = reply->step;
  result.time = reply->time;
  result.ids = std::move(reply->ids);
  return result;
}

CommandResult Client::Send(body_cmd_t command) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  // lcm-gen sizes arrays by their count fields, so keep them consistent.
  command.num_points = static_cast<int32_t>(command.points.size());
  for (std::vector<double>& point : command.points) point.resize(3);
  command.num_parts = static_cast<int32_t>(command.part_shape.size());
  command.num_part_points = static_cast<int32_t>(command.part_points.size());
  command.num_mesh_indices = static_cast<int32_t>(command.mesh_indices.size());
  command.num_heights = static_cast<int32_t>(command.heights.size());
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kBodyCmd), command.request_id, buffer.data(),
                 static_cast<int>(buffer.size()));
}

CommandResult Client::Send(scene_cmd_t command, ProgressCallback progress) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  if (progress) {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_callbacks_[command.request_id] = std::move(progress);
  }
  command.num_params = static_cast<int32_t>(command.param_names.size());
  command.param_values.resize(command.param_names.size());
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kSceneCmd), command.request_id, buffer.data(),
                 static_cast<int>(buffer.size()));
}

CommandResult Client::Step(int32_t n, ProgressCallback progress) {
  uint64_t states_before = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    states_before = states_received_;
  }
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::STEP);
  command.steps = n;
  CommandResult result = Send(command, std::move(progress));
  if (!result.ok()) return result;
  const Clock::time_point deadline = Clock::now() + options_.reply_timeout;
  // The server publishes the last step's STATE before the reply, but the two
  // may be received in either order; a state from before the command (e.g.
  // from before a RESET, with a larger step) must not count.
  std::unique_lock<std::mutex> lock(mutex_);
  const bool arrived = changed_.wait_until(lock, deadline, [&] {
    return states_received_ > states_before && latest_state_ &&
           latest_state_->step >= result.step;
  });
  if (!arrived) {
    result.code = ReplyCode::kTimeout;
    result.message = "STEP replied (step " + std::to_string(result.step) +
                     ") but no STATE of that step arrived on " +
                     Channel(protocol::kState);
  }
  return result;
}

void Client::HandleProgress(const progress_t* progress) {
  ProgressCallback callback;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (progress->client_id != options_.client_id) return;
    auto it = heard_.find(progress->request_id);
    if (it == heard_.end()) return;
    it->second = Clock::now();
    auto cb = progress_callbacks_.find(progress->request_id);
    if (cb != progress_callbacks_.end()) {
      callback = cb->second;
      ++progress_in_flight_;
    }
    changed_.notify_all();
  }
  if (!callback) return;
  callback(*progress);
  std::lock_guard<std::mutex> lock(mutex_);
  --progress_in_flight_;
  changed_.notify_all();
}

// Each handler runs the callbacks before it hands the message to waiting
// commands, so that when Step() returns, OnState has already seen its state.
void Client::HandleReply(const lcm::ReceiveBuffer*, const std::string&,
                         const reply_t* reply) {
  for (const auto& callback : Snapshot(mutex_, callbacks_->reply)) {
    callback(*reply);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (reply->client_id != options_.client_id) return;
  auto it = pending_.find(reply->request_id);
  if (it != pending_.end() && !it->second) {
    it->second = *reply;
    changed_.notify_all();
  }
}

// The decoded message is moved into latest_state_ once the callbacks have
// read it: a lockstep cycle copies no STATE.
void Client::HandleState(const lcm::ReceiveBuffer*, const std::string&,
                         state_t* state) {
  for (const auto& callback : Snapshot(mutex_, callbacks_->state)) {
    callback(*state);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  latest_state_ = std::move(*state);
  ++states_received_;
  changed_.notify_all();
}

void Client::HandleContacts(const lcm::ReceiveBuffer*, const std::string&,
                            const contacts_t* contacts) {
  for (const auto& callback : Snapshot(mutex_, callbacks_->contacts)) {
    callback(*contacts);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  latest_contacts_ = *contacts;
}

void Client::HandleStatus(const lcm::ReceiveBuffer*, const std::string&,
                          const status_t* status) {
  for (const auto& callback : Snapshot(mutex_, callbacks_->status)) {
    callback(*status);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  latest_status_ = *status;
  changed_.notify_all();
}

int Client::OnState(StateCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->state[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

int Client::OnContacts(ContactsCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->contacts[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

int Client::OnStatus(StatusCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->status[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

int Client::OnReply(ReplyCallback callback) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->reply[callbacks_->next_id] = std::move(callback);
  return callbacks_->next_id++;
}

void Client::RemoveCallback(int id) {
  std::lock_guard<std::mutex> lock(mutex_);
  callbacks_->state.erase(id);
  callbacks_->contacts.erase(id);
  callbacks_->status.erase(id);
  callbacks_->reply.erase(id);
  callbacks_->sensors.erase(id);
  callbacks_->joint_state.erase(id);
}

std::optional<state_t> Client::LatestState() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_state_;
}

std::optional<contacts_t> Client::LatestContacts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_contacts_;
}

std::optional<status_t> Client::LatestStatus() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_status_;
}

bool Client::WaitForServer(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout,
                           [&] { return latest_status_.has_value(); });
}

std::optional<state_t> Client::WaitForState(
    const std::function<bool(const state_t&)>& predicate,
    std::chrono::milliseconds timeout) {
  const Clock::time_point deadline = Clock::now() + timeout;
  uint64_t seen = 0;  // states_received_ of the last state checked
  while (true) {
    std::optional<state_t> state;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!changed_.wait_until(lock, deadline, [&] {
            return latest_state_ && states_received_ != seen;
          })) {
        return std::nullopt;
      }
      seen = states_received_;
      state = latest_state_;
    }
    // Outside the lock, so the predicate may call LatestStatus() and friends.
    if (predicate(*state)) return state;
  }
}

}  // namespace contactsim
