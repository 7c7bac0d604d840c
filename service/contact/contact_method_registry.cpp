#include "service/contact/contact_method_registry.h"

#include <Eigen/Core>

#include "service/contact/barrier/barrier_method.h"
#include "service/contact/impulse/impulse_method.h"
#include "service/contact/lcp/lcp_method.h"
#include "service/contact/penalty/penalty_method.h"
#include "service/contact/soft/soft_method.h"
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

template <class M>
std::unique_ptr<ContactMethod> Make() {
  return std::make_unique<M>();
}

}  // namespace

// The contracts (docs/physics.md, "Method contract"): what each method's
// header says it simulates; tests/contact/method_contract_test.cpp checks
// every "yes" by a scenario and tests/server/ every "no" by a refusal.
// The names are the protocol's (lcmtypes/protocol.toml, `methods`), which the
// clients and the viewer offer; method_contract_test.cpp checks that they agree.
const std::vector<ContactMethodEntry>& ContactMethodTable() {
  //                           joints restitution kinematic friction compound contact_forces triangle_surfaces
  //                           joint_couplings
  // joint_couplings: impulse, penalty and soft solve their joints with the
  // shared solvers of joints/, which carry the mimics' rows; xpbd's
  // positional joints and lcp's joint rows inside its complementarity solve
  // do not, and refuse a mimic
  static const std::vector<ContactMethodEntry> table = {
      {"impulse", Make<ImpulseMethod>, {true, true, true, "coulomb disk", true, true, true, true}},
      {"penalty", Make<PenaltyMethod>,
       {true, true, true, "regularized: tangential spring with a coulomb disk limit", true, true, true, true}},
      {"xpbd", Make<XpbdMethod>, {true, true, true, "coulomb disk (positional static, velocity-level dynamic)", true, true}},
      {"lcp", Make<LcpMethod>, {true, true, true, "coulomb disk (solver=pgs) or coulomb pyramid (solver=lemke)", true, true}},
      // barrier: the implicit step is inelastic (no restitution), and a
      // kinematic body is moved to its end pose before the solve
      // (barrier_solver.cpp, Setup), so its motion reaches neither the CCD
      // nor the friction: a rising platform passes through what rests on it.
      // Its distances come from one BodyGeometry per body (one rounding
      // radius), not from the narrowphase: it takes no compound bodies; its
      // contacts carry the barrier force alone, not the friction. A
      // triangle mesh or heightfield is a static body whose triangles it
      // looks up near each primitive (barrier/surface_primitives.h)
      {"barrier", Make<BarrierMethod>,
       {false, false, false, "regularized: smoothed coulomb disk, lagged (eps_v)", false, false, true}},
      {"soft", Make<SoftMethod>, {true, true, true, "coulomb disk", true, true, true, true}},
  };
  return table;
}

const ContactMethodEntry* FindContactMethod(const std::string& name) {
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    if (name == e.name) return &e;
  }
  return nullptr;
}

std::vector<std::string> ContactMethodNames() {
  std::vector<std::string> names;
  for (const ContactMethodEntry& e : ContactMethodTable()) names.push_back(e.name);
  return names;
}

Status CreateContactMethod(const std::string& name, std::unique_ptr<ContactMethod>* out) {
  PinEigenBlockSizes();  // before any method's first step
  if (const ContactMethodEntry* e = FindContactMethod(name)) {
    *out = e->create();
    return Status::Ok();
  }
  std::string known;
  for (const std::string& n : ContactMethodNames()) known += (known.empty() ? "" : ", ") + n;
  return Status::NotFound("unknown contact method \"" + name + "\" (known: " + known + ")");
}

Status MakeContactMethod(const std::string& name, const ParamMap& params, std::shared_ptr<ContactMethod>* method) {
  std::unique_ptr<ContactMethod> m;
  Status st = CreateContactMethod(name, &m);
  if (!st.ok()) return st;
  if (!(st = m->SetParams(params)).ok()) return st;
  *method = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
