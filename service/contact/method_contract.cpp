#include "service/contact/method_contract.h"

namespace contactsim {

std::string DescribeContract(const MethodContract& c) {
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  return std::string("joints=") + yes(c.joints) + "; restitution=" + yes(c.restitution) +
         "; kinematic=" + yes(c.kinematic_bodies) + "; contact_forces=" + yes(c.contact_forces) + "; friction=" + c.friction;
}

}  // namespace contactsim
