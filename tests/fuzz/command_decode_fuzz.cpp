// libFuzzer target: one command channel's decoder (CONTACTSIM_FUZZ_CHANNEL,
// set by the build) on arbitrary bytes. The decoder must return a status
// for every input: no crash, no exception, no sanitizer finding, and no
// allocation sized from the input beyond its own length.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "service/server/command_channels.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const contactsim::CommandChannel* channel = contactsim::ChannelOfSuffix(CONTACTSIM_FUZZ_CHANNEL);
  if (channel == nullptr) std::abort();
  contactsim::Command cmd;
  const contactsim::Status st = channel->decode(data, static_cast<int>(size), contactsim::DecodeContext{}, &cmd);
  // a decoded command always names its sender's request (or failed as bytes)
  if (st.ok() && cmd.payload.size() != size) std::abort();
  return 0;
}
