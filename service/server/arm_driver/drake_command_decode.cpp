#include "service/server/arm_driver/drake_command_decode.h"

#include <cmath>

namespace contactsim {

Status CheckFiniteArray(const std::vector<double>& values, const char* field) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return Status::InvalidArgument(std::string(field) + "[" + std::to_string(i) + "] is " +
                                     std::to_string(values[i]) + ", not a finite number");
    }
  }
  return Status::Ok();
}

Status CheckFiniteValue(double value, const char* field) {
  if (std::isfinite(value)) return Status::Ok();
  return Status::InvalidArgument(std::string(field) + " is " + std::to_string(value) + ", not a finite number");
}

}  // namespace contactsim
