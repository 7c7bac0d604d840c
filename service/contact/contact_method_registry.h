// The registry of contact methods: one row per method with its name, its
// factory and its contract (method_contract.h), so that a new method is one
// row and ContactMethodNames(), CreateContactMethod() and the server's
// capability checks (method_support.h) all read the same table.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/method_contract.h"

namespace contactsim {

struct ContactMethodEntry {
  const char* name;
  std::unique_ptr<ContactMethod> (*create)();  // with the method's default parameters
  MethodContract contract;
};

// Every method, in a stable order (that of ContactMethodNames()).
const std::vector<ContactMethodEntry>& ContactMethodTable();

// The row of the method named `name`, or nullptr.
const ContactMethodEntry* FindContactMethod(const std::string& name);

// Builds a contact method by name with text parameters, validating both
// (the name against the table, the parameters against the method's ParamTable).
Status MakeContactMethod(const std::string& name, const ParamMap& params, std::shared_ptr<ContactMethod>* method);

}  // namespace contactsim
