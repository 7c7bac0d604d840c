#include "service/server/arm_driver/arm_protocol.h"

#include "service/server/arm_driver/iiwa_status_builder.h"
#include "service/server/arm_driver/panda_status_builder.h"
#include "service/server/publisher.h"

namespace contactsim {
namespace {

// Builds a status message with `build` and publishes it.
template <typename Msg>
Status PublishStatus(Status (*build)(double, const ArmJointReadings&, Msg*), const Publisher& publisher,
                     const std::string& channel, double sim_time_s, const ArmJointReadings& readings) {
  Msg m;
  const Status st = build(sim_time_s, readings, &m);
  if (st.ok()) publisher.Publish(channel, m);
  return st;
}

// Drake's iiwa driver (manipulation/kuka_iiwa, kIiwaLcmStatusPeriod = 5 ms)
// reports at 200 Hz; the Franka driver (drake-franka-driver) reports once
// per libfranka control cycle, 1 kHz.
const ArmProtocol kProtocols[] = {
    {"iiwa", "IIWA", "lcmt_iiwa_command", "lcmt_iiwa_status", 200.0, DecodeIiwaCommand,
     [](const Publisher& p, const std::string& c, double t, const ArmJointReadings& r) {
       return PublishStatus(BuildIiwaStatus, p, c, t, r);
     }},
    {"panda", "PANDA", "lcmt_panda_command", "lcmt_panda_status", 1000.0, DecodePandaCommand,
     [](const Publisher& p, const std::string& c, double t, const ArmJointReadings& r) {
       return PublishStatus(BuildPandaStatus, p, c, t, r);
     }},
};

}  // namespace

const ArmProtocol* FindArmProtocol(const std::string& name) {
  for (const ArmProtocol& p : kProtocols) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

std::string ArmProtocolNames() {
  std::string names;
  const size_t n = sizeof(kProtocols) / sizeof(kProtocols[0]);
  for (size_t i = 0; i < n; ++i) {
    names += (i == 0 ? "\"" : (i + 1 == n ? " or \"" : ", \"")) + std::string(kProtocols[i].name) + "\"";
  }
  return names;
}

}  // namespace contactsim
