// The checks of a mimic (physics/joint.h, JointMimic): a mimic couples two
// joint coordinates of the same unit (rad with rad, m with m), so both
// joints must be hinges or both sliders; a mimic of itself or a cycle of
// mimics would ask q = m q + o, which has no solution or infinitely many.
#include <algorithm>
#include <cmath>
#include <string>

#include "service/physics/joint.h"

namespace contactsim {
namespace {

const Joint* FindIn(const std::vector<Joint>& joints, JointId id) {
  const auto it = std::find_if(joints.begin(), joints.end(), [id](const Joint& j) { return j.id == id; });
  return it == joints.end() ? nullptr : &*it;
}

}  // namespace

Status CheckJointMimic(const std::vector<Joint>& joints, JointId follower, const JointMimic& mimic) {
  const std::string who = "joint " + std::to_string(follower);
  const Joint* f = FindIn(joints, follower);
  if (f == nullptr) return Status::NotFound("unknown joint id " + std::to_string(follower));
  if (mimic.master == follower) return Status::InvalidArgument(who + " cannot mimic itself");
  const Joint* m = FindIn(joints, mimic.master);
  if (m == nullptr) {
    return Status::InvalidArgument(who + " mimics joint " + std::to_string(mimic.master) + ", which does not exist");
  }
  if (!HasJointCoordinate(f->kind) || f->kind != m->kind) {
    return Status::InvalidArgument(who + " (" + JointKindName(f->kind) + ") cannot mimic joint " +
                                   std::to_string(m->id) + " (" + JointKindName(m->kind) +
                                   "): a mimic couples two hinges or two prismatic joints");
  }
  if (!std::isfinite(mimic.multiplier) || !std::isfinite(mimic.offset)) {
    return Status::InvalidArgument(who + " mimic multiplier and offset must be finite, got " +
                                   std::to_string(mimic.multiplier) + " and " + std::to_string(mimic.offset));
  }
  // follow the masters up; every step visits another joint, so the walk
  // ends within joints.size() steps unless the existing mimics hold a cycle
  JointId at = mimic.master;
  for (size_t steps = 0; at != 0 && steps <= joints.size(); ++steps) {
    if (at == follower) {
      return Status::InvalidArgument(who + " mimicking joint " + std::to_string(mimic.master) +
                                     " would close a cycle of mimics");
    }
    const Joint* next = FindIn(joints, at);
    at = next != nullptr ? next->mimic.master : 0;
  }
  return Status::Ok();
}

}  // namespace contactsim
