#include "service/contact/method_support.h"

#include "service/contact/contact_method_registry.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

MethodContract ContractOf(const std::string& method) {
  const ContactMethodEntry* e = FindContactMethod(method);
  return e ? e->contract : MethodContract{};
}

// "impulse, penalty, xpbd or lcp": the methods whose contract has `what`.
std::string MethodsWith(bool MethodContract::*what) {
  std::vector<std::string> names;
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    if (e.contract.*what) names.push_back(e.name);
  }
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  return text;
}

}  // namespace

Status CheckMethodSupports(const std::string& method, const World& world) {
  const MethodContract contract = ContractOf(method);
  if (!world.joints().empty() && !contract.joints) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate joints; the world holds " +
                                      std::to_string(world.joints().size()) + " joint(s): remove them or choose " +
                                      MethodsWith(&MethodContract::joints));
  }
  if (contract.joints && !contract.joint_couplings && world.HasJointMimics()) {
    return Status::FailedPrecondition("contact method " + method +
                                      " does not simulate mimic joints (joint couplings); the world holds a mimic "
                                      "joint: remove it or choose " +
                                      MethodsWith(&MethodContract::joint_couplings));
  }
  if (!world.sensors.contacts.empty() && !contract.contact_forces) {
    return Status::FailedPrecondition("contact method " + method + " does not report contact forces; the world holds " +
                                      std::to_string(world.sensors.contacts.size()) +
                                      " contact sensor(s): remove them or choose " +
                                      MethodsWith(&MethodContract::contact_forces));
  }
  for (const RigidBody& b : world.bodies()) {
    const std::string what = "body " + std::to_string(b.id) + (b.name.empty() ? "" : " \"" + b.name + "\"");
    const Status st = CheckMethodAcceptsBody(method, b, what);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

Status CheckMethodAcceptsJoint(const std::string& method) {
  if (ContractOf(method).joints) return Status::Ok();
  return Status::FailedPrecondition("contact method " + method + " does not simulate joints: choose " +
                                    MethodsWith(&MethodContract::joints) + " before adding one");
}

Status CheckMethodAcceptsMimic(const std::string& method) {
  if (ContractOf(method).joint_couplings) return Status::Ok();
  return Status::FailedPrecondition("contact method " + method +
                                    " does not simulate mimic joints (joint couplings): choose " +
                                    MethodsWith(&MethodContract::joint_couplings) + " before loading a model with one");
}

Status CheckMethodAcceptsContactSensor(const std::string& method) {
  if (ContractOf(method).contact_forces) return Status::Ok();
  return Status::FailedPrecondition("contact method " + method +
                                    " does not report contact forces, so a contact sensor would read nothing: choose " +
                                    MethodsWith(&MethodContract::contact_forces) + " before adding one");
}

Status CheckMethodAcceptsBody(const std::string& method, const RigidBody& body, const std::string& what) {
  const MethodContract contract = ContractOf(method);
  if (body.material.restitution > 0.0 && !contract.restitution) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate restitution: " + what +
                                      " has restitution " + FormatValue(body.material.restitution) +
                                      "; give it restitution 0 or choose " +
                                      MethodsWith(&MethodContract::restitution));
  }
  if (body.shape.type == ShapeType::kCompound && !contract.compound_bodies) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate compound bodies: " + what +
                                      " is a compound of " + std::to_string(body.shape.compound->children.size()) +
                                      " shape(s); give it one shape centred at its centre of mass or choose " +
                                      MethodsWith(&MethodContract::compound_bodies));
  }
  if (body.shape.IsTriangleSurface() && !contract.triangle_surfaces) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate triangle meshes or heightfields: " +
                                      what + " is a " + ShapeTypeName(body.shape.type) + "; choose " +
                                      MethodsWith(&MethodContract::triangle_surfaces));
  }
  if (body.motion == MotionType::kKinematic && !contract.kinematic_bodies) {
    return Status::FailedPrecondition("contact method " + method + " does not simulate kinematic bodies: " + what +
                                      " is kinematic; make it dynamic or fixed, or choose " +
                                      MethodsWith(&MethodContract::kinematic_bodies));
  }
  return Status::Ok();
}

}  // namespace contactsim
