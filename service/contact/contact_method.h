// The contact method interface. A method owns the whole step
// (docs/architecture.md): the methods differ in what they need (collision time,
// forces before integration, a global solve), so each one calls the
// collision detector and the integrator itself.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "service/collision/collision_detector.h"
#include "service/collision/contact.h"
#include "service/contact/param_doc.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

// Parameters arrive as text ("0.5", "pgs") and are validated by the method.
using ParamMap = std::map<std::string, std::string>;

// What Contact::normal_value and tangent_value hold after a step.
enum class ContactValueKind { kImpulse, kForce };

struct StepStats {
  int contacts = 0;
  int iterations = 0;          // solver iterations (summed over sub-steps)
  int substeps = 0;            // collision-time sub-steps taken
  double residual = 0.0;       // method specific, documented by the method
  double max_penetration = 0.0;// m, deepest contact at the end of the step
  double stiffness = 0.0;      // method specific (barrier: kappa, N/m); 0 when none
};

class ContactMethod {
 public:
  virtual ~ContactMethod() = default;
  virtual const char* Name() const = 0;
  virtual ContactValueKind ValueKind() const = 0;
  // Validates every entry before changing any; on error nothing changes and
  // the message names the parameter and the value.
  virtual Status SetParams(const ParamMap& params) = 0;
  virtual ParamMap Params() const = 0;
  // Every parameter SetParams takes, in declaration order, with its default
  // (param_table.h: the same table parses them and writes Params()).
  virtual std::vector<ParamDoc> ParamDocs() const = 0;
  // Advances the world by world.dt and leaves the step's contacts in
  // `contacts` with their values.
  virtual StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) = 0;
  // Whether Step must fill in the contacts' values and end-of-step depths
  // and StepStats::max_penetration (the contact report). On by default:
  // the server's CONTACTS channel, its sensors and status read them, and
  // island sleep keeps a sleeping body's contacts as reported. A caller
  // that reads none of it (the scene bench) turns it off; a method may then
  // leave `contacts` as detected, each pair's points without values and
  // max_penetration 0, which is what island sleep's islands read
  // (island_sleep.h). The step itself is the same either way.
  void RequestContactReport(bool on) { contact_report_ = on; }
  bool contact_report() const { return contact_report_; }
  // Drops warm-start and other caches (on a switch, reset or scene load).
  virtual void ResetCaches() {}
  // The caches an exact continuation needs (warm starts, friction anchors),
  // as opaque bytes for snapshots (service/scene/snapshot.h); a method
  // without caches saves nothing. LoadState replaces the caches with saved
  // ones, or fails naming what was wrong and leaves them as they were.
  virtual std::string SaveState() const { return {}; }
  virtual Status LoadState(const std::string& bytes) {
    if (bytes.empty()) return Status::Ok();
    return Status::InvalidArgument(std::string("contact method ") + Name() + " keeps no state, got " +
                                   std::to_string(bytes.size()) + " bytes");
  }

 private:
  bool contact_report_ = true;
};

// Known method names, in a stable order.
std::vector<std::string> ContactMethodNames();
// Creates a method by name with its default parameters.
Status CreateContactMethod(const std::string& name, std::unique_ptr<ContactMethod>* out);

}  // namespace contactsim
