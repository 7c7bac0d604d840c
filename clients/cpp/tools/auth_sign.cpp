// contactsim-auth-sign: signs or verifies one message with the C++ signature
// library (docs/protocol.md, "Authentication"), so that a test can check
// that the Python client signs byte for byte the same.
//
//   contactsim-auth-sign --key-file F --channel C [--seq N] < payload > signed
//   contactsim-auth-sign --key-file F --channel C --verify < signed
//
// Signing writes the payload and its trailer (with --seq, that seq; else
// the clock's). --verify prints "ok <payload bytes> <seq>" and exits 0, or
// prints why and exits 1. A bad key file or command line exits 2.
#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>

#include <CLI/CLI.hpp>

#include "contactsim/signature.h"

int main(int argc, char** argv) {
  CLI::App app{"Sign (or --verify) one message read from stdin."};
  std::string key_file, channel;
  uint64_t seq = 0;
  bool verify = false;
  app.add_option("--key-file", key_file, "auth key file")->required();
  app.add_option("--channel", channel, "LCM channel the message is for")->required();
  CLI::Option* seq_opt = app.add_option("--seq", seq, "seq to sign with (default: the clock)");
  app.add_flag("--verify", verify, "check a signed message instead");
  CLI11_PARSE(app, argc, argv);

  std::string key, error;
  if (!contactsim::LoadAuthKey(key_file, &key, &error)) {
    std::cerr << "contactsim-auth-sign: " << error << "\n";
    return 2;
  }
  const std::string input((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  const int size = static_cast<int>(input.size());
  if (verify) {
    const contactsim::Verified v = contactsim::VerifySignature(key, channel, input.data(), size);
    if (!v.ok) {
      std::printf("%s\n", v.error.c_str());
      return 1;
    }
    std::printf("ok %d %" PRIu64 "\n", v.payload_size, v.seq);
    return 0;
  }
  const std::string out = seq_opt->count() > 0
                              ? input + contactsim::SignatureTrailer(key, channel, input.data(), size, seq)
                              : contactsim::Signer(key).Sign(channel, input.data(), size);
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}
