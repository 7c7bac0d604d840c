// A world, a detector and a contact method created through the registry by
// name, for tests that drive a method step by step.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "service/contact/contact_method.h"

namespace contactsim {
namespace testing {

struct MethodSim {
  World world;
  CollisionDetector detector;
  std::unique_ptr<ContactMethod> method;
  ContactSet contacts;
  explicit MethodSim(const std::string& name, const ParamMap& params = {}) {
    Status st = CreateContactMethod(name, &method);
    EXPECT_TRUE(st.ok()) << st.message();
    if (!st.ok()) return;
    st = method->SetParams(params);
    EXPECT_TRUE(st.ok()) << st.message();
  }
  StepStats Step() { return method->Step(world, detector, &contacts); }
};

}  // namespace testing
}  // namespace contactsim
