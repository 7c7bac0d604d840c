#include <memory>

#include "service/contact/contact_method.h"
#include "service/contact/barrier/barrier_method.h"
#include "service/contact/impulse_method.h"
#include "service/contact/lcp/lcp_method.h"
#include "service/contact/penalty_method.h"
#include "service/contact/xpbd/xpbd_method.h"

namespace contactsim {

std::vector<std::string> ContactMethodNames() { return {"impulse", "penalty", "xpbd", "lcp", "barrier"}; }

Status CreateContactMethod(const std::string& name, std::unique_ptr<ContactMethod>* out) {
  if (name == "impulse") {
    *out = std::make_unique<ImpulseMethod>();
    return Status::Ok();
  }
  if (name == "penalty") {
    *out = std::make_unique<PenaltyMethod>();
    return Status::Ok();
  }
  if (name == "xpbd") {
    *out = std::make_unique<XpbdMethod>();
    return Status::Ok();
  }
  if (name == "lcp") {
    *out = std::make_unique<LcpMethod>();
    return Status::Ok();
  }
  if (name == "barrier") {
    *out = std::make_unique<BarrierMethod>();
    return Status::Ok();
  }
  std::string known;
  for (const std::string& n : ContactMethodNames()) known += (known.empty() ? "" : ", ") + n;
  return Status::NotFound("unknown contact method \"" + name + "\" (known: " + known + ")");
}

}  // namespace contactsim
