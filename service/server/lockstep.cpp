#include "service/server/lockstep.h"

#include <cstdio>

#include "service/physics/fnv1a.h"

namespace contactsim {

const char* LatePolicyName(LatePolicy policy) {
  switch (policy) {
    case LatePolicy::kWait: return "wait";
    case LatePolicy::kReuse: return "reuse";
    case LatePolicy::kDrop: return "drop";
  }
  return "?";
}

Status ParseLatePolicy(const std::string& text, LatePolicy* policy) {
  for (LatePolicy p : {LatePolicy::kWait, LatePolicy::kReuse, LatePolicy::kDrop}) {
    if (text == LatePolicyName(p)) {
      *policy = p;
      return Status::Ok();
    }
  }
  return Status::InvalidArgument("late_policy must be \"wait\", \"reuse\" or \"drop\", got \"" + text + "\"");
}

Status Lockstep::Register(const std::string& id, LatePolicy policy, double timeout_s) {
  if (id.empty()) return Status::InvalidArgument("client_id must not be empty to register a controller");
  Controller& c = controllers_[id];  // registering again updates the policy
  c.policy = policy;
  c.timeout_s = timeout_s;
  return Status::Ok();
}

Status Lockstep::Release(const std::string& id) {
  if (controllers_.erase(id) == 0) return Status::NotFound("\"" + id + "\" is not a registered controller");
  return Status::Ok();
}

Status Lockstep::Offer(ControllerInput input, int64_t next_step) {
  const auto it = controllers_.find(input.controller);
  if (it == controllers_.end()) {
    return Status::FailedPrecondition("\"" + input.controller + "\" is not a registered controller");
  }
  const Controller& c = it->second;
  if (input.step < next_step && !c.last.controller.empty() && input.step == c.last.step &&
      input.request_id == c.last.request_id) {
    return Status::Ok();  // a resend of the input just applied (it answered a repeated STATE): nothing to do
  }
  if (input.step < next_step) {
    return Status::FailedPrecondition("input for step " + std::to_string(input.step) + " came after it was taken (next step " +
                                      std::to_string(next_step) + ")");
  }
  it->second.queued[input.step] = std::move(input);
  return Status::Ok();
}

bool Lockstep::Ready(int64_t step) const {
  for (const auto& [id, c] : controllers_) {
    if (c.queued.count(step) == 0) return false;
  }
  return true;
}

double Lockstep::NextDeadline(int64_t step) const {
  double deadline = -1.0;
  for (const auto& [id, c] : controllers_) {
    if (c.queued.count(step) != 0 || c.policy == LatePolicy::kWait) continue;
    if (deadline < 0.0 || c.timeout_s < deadline) deadline = c.timeout_s;
  }
  return deadline;
}

std::vector<std::string> Lockstep::ResolveLate(int64_t step, double waited_s) {
  std::vector<std::string> lines;
  for (auto it = controllers_.begin(); it != controllers_.end();) {
    Controller& c = it->second;
    const bool late = c.queued.count(step) == 0 && c.policy != LatePolicy::kWait && waited_s >= c.timeout_s;
    if (!late) {
      ++it;
      continue;
    }
    char text[256];
    std::snprintf(text, sizeof text, "controller \"%s\" late for step %lld after %.3f s: %s", it->first.c_str(),
                  static_cast<long long>(step), waited_s,
                  c.policy == LatePolicy::kReuse ? "reusing its last input" : "dropped");
    lines.push_back(text);
    last_late_event_ = text;
    ++late_events_;
    ++c.late;
    if (c.policy == LatePolicy::kReuse) {
      ControllerInput again = c.last;
      again.controller = it->first;
      again.step = step;
      c.queued[step] = std::move(again);
      ++it;
    } else {
      it = controllers_.erase(it);
    }
  }
  return lines;
}

std::vector<ControllerInput> Lockstep::Take(int64_t step) {
  std::vector<ControllerInput> out;
  for (auto& [id, c] : controllers_) {
    // inputs for earlier steps can no longer apply
    while (!c.queued.empty() && c.queued.begin()->first < step) c.queued.erase(c.queued.begin());
    const auto it = c.queued.find(step);
    if (it == c.queued.end()) continue;
    c.last = it->second;
    out.push_back(std::move(it->second));
    c.queued.erase(it);
  }
  return out;
}

std::string Lockstep::Describe() const {
  std::string text;
  for (const auto& [id, c] : controllers_) {
    char item[256];
    std::snprintf(item, sizeof item, "%s%s (%s, %g s, late %lld)", text.empty() ? "" : ", ", id.c_str(),
                  LatePolicyName(c.policy), c.timeout_s, static_cast<long long>(c.late));
    text += item;
  }
  return text;
}

uint64_t DigestInputs(const std::vector<ControllerInput>& inputs) {
  if (inputs.empty()) return 0;
  Fnv1a f;
  for (const ControllerInput& in : inputs) {
    f.Bytes(in.controller.data(), in.controller.size());
    f.Bytes(&in.step, sizeof in.step);
    for (const BodyInput& b : in.bodies) {
      f.Bytes(&b.body, sizeof b.body);
      f.Vector(b.force);
      f.Vector(b.torque);
    }
    const ActuatorUpdate& u = in.joints;
    if (u.empty()) continue;
    f.Bytes(&u.fields, sizeof u.fields);
    for (size_t i = 0; i < u.values.size(); ++i) {
      const JointActuator& a = u.values[i];
      if (i < u.joints.size()) f.Bytes(&u.joints[i], sizeof u.joints[i]);
      for (double v : {a.torque, a.target_position, a.target_velocity, a.kp, a.kd, a.effort_limit, a.velocity_limit}) {
        f.Double(v);
      }
    }
  }
  return f.h;
}

}  // namespace contactsim
