#include <Eigen/Core>
#include <memory>

#include "service/contact/contact_method.h"
#include "service/contact/barrier/barrier_method.h"
#include "service/contact/impulse_method.h"
#include "service/contact/lcp/lcp_method.h"
#include "service/contact/penalty_method.h"
#include "service/contact/xpbd/xpbd_method.h"

namespace contactsim {
namespace {

// Eigen sizes the blocks of a large matrix product by the CPU's caches,
// queried at run time, and the block depth sets the order in which each
// entry's terms are summed: products deeper than 504 terms (Lemke with many
// joint rows, mixed_lcp.cpp) summed differently with a 32 KiB L1 than with
// a 48 KiB one. One size for every machine (docs/snapshots.md, "Determinism
// across builds"); Eigen's own x86 defaults.
void PinEigenBlockSizes() {
  static const bool pinned = [] {
    Eigen::setCpuCacheSizes(32 * 1024, 256 * 1024, 2 * 1024 * 1024);
    return true;
  }();
  (void)pinned;
}

}  // namespace

std::vector<std::string> ContactMethodNames() { return {"impulse", "penalty", "xpbd", "lcp", "barrier"}; }

Status CreateContactMethod(const std::string& name, std::unique_ptr<ContactMethod>* out) {
  PinEigenBlockSizes();  // before any method's first step
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
