#include "service/contact/method_support.h"

namespace contactsim {

bool MethodSupportsJoints(const std::string& method) { return method != "barrier"; }

Status CheckMethodSupports(const std::string& method, const World& world) {
  if (!world.joints().empty() && !MethodSupportsJoints(method)) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate joints; the world holds " +
                                      std::to_string(world.joints().size()) +
                                      " joint(s): remove them or choose impulse, penalty, xpbd or lcp");
  }
  return Status::Ok();
}

}  // namespace contactsim
