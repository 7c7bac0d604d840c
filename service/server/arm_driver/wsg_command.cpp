#include "service/server/arm_driver/wsg_command.h"

#include <drake/lcmt_schunk_wsg_command.hpp>

#include <string>

#include "service/physics/validation.h"
#include "service/server/arm_driver/drake_command_decode.h"

namespace contactsim {

Status DecodeWsgCommand(const void* data, int size, WsgCommand* out) {
  return DecodeDrakeCommand<drake::lcmt_schunk_wsg_command>(
      data, size, kMaxWsgCommandBytes, "lcmt_schunk_wsg_command", &out->utime, [&](const auto& m) {
        Status st = CheckFiniteValue(m.target_position_mm, "target_position_mm");
        if (st.ok()) st = CheckFiniteValue(m.force, "force");
        if (!st.ok()) return st;
        if (!(m.force > 0)) {
          return Status::InvalidArgument("force is " + FormatValue(m.force) +
                                         " N; the grip force limit must be > 0 N");
        }
        out->target_position_mm = m.target_position_mm;
        out->force = m.force;
        return Status::Ok();
      });
}

}  // namespace contactsim
