// libFuzzer target: arbitrary payloads on any command channel into a live
// SimServer with a small world, then a few steps. The first byte picks the
// channel; the rest is the payload. Whatever decodes is applied, so the
// apply path (bodies, joints, methods, snapshots, lockstep) must survive
// every command that passes decoding, too. The world persists across
// inputs (as a long-running server's does), bounded by small limits.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>

#include "service/contact/contact_method_registry.h"
#include "service/server/command_decoder.h"
#include "service/server/sim_server.h"

namespace {

class NullTransport : public contactsim::Transport {
 public:
  void Publish(const std::string&, const void*, int) override {}
};

contactsim::SimServer* MakeServer() {
  using namespace contactsim;
  static NullTransport transport;
  ServerOptions o;
  o.prefix = "F";
  o.start_paused = true;
  o.mode = RunMode::kFreeRun;
  o.max_bodies = 24;
  o.max_joints = 8;
  o.write_files = false;          // SNAPSHOT to a path writes nothing
  o.max_commands_per_second = 0;  // the fuzzer is one client sending fast
  o.decode_limits.max_convex_points = 64;
  o.snapshot_every = 50;
  o.max_snapshots = 4;
  static SimServer server(o, &transport);
  std::shared_ptr<ContactMethod> method;
  if (!MakeContactMethod("impulse", {}, &method).ok() || !server.Init(nullptr, method).ok()) std::abort();
  return &server;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static contactsim::SimServer* server = MakeServer();
  static const std::vector<std::string> channels = server->CommandChannelNames();
  if (size == 0) return 0;
  server->OnMessage(channels[data[0] % channels.size()], data + 1, static_cast<int>(size - 1));
  // apply, and take at most a few of the steps a STEP may have asked for
  for (int i = 0; i < 4 && server->Tick(); ++i) {
  }
  return 0;
}
