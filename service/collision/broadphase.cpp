// The broadphase factory: a name from the server config or a command turns
// into an implementation, or into an error that lists the known names.
#include "service/collision/broadphase.h"

#include "service/collision/naive_broadphase.h"
#include "service/collision/sweep_and_prune.h"

namespace contactsim {

Status CreateBroadphase(const std::string& name, std::unique_ptr<Broadphase>* out) {
  if (name == "naive") {
    *out = std::make_unique<NaiveBroadphase>();
  } else if (name == "sap") {
    *out = std::make_unique<SweepAndPrune>();
  } else {
    return Status::InvalidArgument("unknown broadphase \"" + name + "\"; known: naive, sap");
  }
  return Status::Ok();
}

}  // namespace contactsim
