// contactsim::Client with an auth key (docs/protocol.md, "Authentication")
// against a stand-in server on real LCM that signs its output and checks
// every command and input as the server does: commands go out signed,
// output that fails its check is dropped and counted, and a client without
// a key still reads signed output. No contactsim-server binary needed.
#include <unistd.h>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "contactsim/client.h"
#include "contactsim/controller.h"
#include "contactsim/signature.h"
#include "test_key.h"

namespace contactsim {
namespace {

using namespace std::chrono_literals;

constexpr auto kWait = 5000ms;  // generous: two cores shared with builds

// Its own port (9800-9899: the C++ integration tests use 7800-8799, the
// Python ones 8800-9799) and prefix per peer, so parallel tests never meet.
std::string UniqueUrl(int n) {
  return "udpm://239.255.76.67:" + std::to_string(9800 + (::getpid() * 7 + n) % 100) + "?ttl=0";
}

// Answers SCENE_CMD with OK replies and records INPUT steps; signs what it
// publishes (unless sign = false) and, with require_signed, refuses what
// fails the checks the server makes.
class SigningPeer {
 public:
  SigningPeer() : url_(UniqueUrl(count_)), prefix_("CLIENTAUTH" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(count_++)),
                  lcm_(url_), signer_(testing::kTestKey) {
    lcm_.subscribeFunction(prefix_ + "_SCENE_CMD", &OnScene, this);
    lcm_.subscribeFunction(prefix_ + "_INPUT", &OnInput, this);
    thread_ = std::thread([this] {
      while (running_) lcm_.handleTimeout(20);
    });
  }
  ~SigningPeer() {
    running_ = false;
    thread_.join();
  }

  ClientOptions Options(std::optional<std::string> key_file) const {
    ClientOptions options;
    options.url = url_;
    options.prefix = prefix_;
    options.reply_timeout = kWait;
    options.auth_key_file = std::move(key_file);
    return options;
  }
  template <typename Msg>
  void Publish(const std::string& suffix, const Msg& msg) {
    std::vector<uint8_t> buf(msg.getEncodedSize());
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    const std::string channel = prefix_ + "_" + suffix;
    const std::string bytes = sign ? signer_.Sign(channel, buf.data(), static_cast<int>(buf.size()))
                                   : std::string(buf.begin(), buf.end());
    lcm_.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
  }
  void PublishState(int64_t step) {
    state_t s{};
    s.step = step;
    Publish("STATE", s);
  }
  std::vector<std::string> refused() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return refused_;
  }
  std::vector<int64_t> inputs() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return inputs_;
  }

  std::atomic<bool> sign{true};
  std::atomic<bool> require_signed{true};

 private:
  // The payload size of an admitted message, or -1 (recorded as refused).
  template <typename Msg>
  int Admit(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Msg* msg) {
    const int size = static_cast<int>(rbuf->data_size);
    if (!require_signed) return msg->decode(rbuf->data, 0, UnsignedSize(rbuf->data, size));
    const Verified v = VerifySignature(testing::kTestKey, channel, rbuf->data, size);
    std::string why = v.error;
    if (v.ok && msg->decode(rbuf->data, 0, v.payload_size) >= 0 &&
        replay_.Accept(msg->client_id, v.seq, WallClockNanoseconds(), kDefaultAuthWindowSeconds, &why)) {
      return v.payload_size;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    refused_.push_back(why);
    return -1;
  }
  static void OnScene(const lcm::ReceiveBuffer* rbuf, const std::string& channel, SigningPeer* peer) {
    scene_cmd_t cmd;
    if (peer->Admit(rbuf, channel, &cmd) < 0) return;
    reply_t reply{};
    reply.client_id = cmd.client_id;
    reply.request_id = cmd.request_id;
    reply.code = reply_t::OK;
    peer->Publish("REPLY", reply);
  }
  static void OnInput(const lcm::ReceiveBuffer* rbuf, const std::string& channel, SigningPeer* peer) {
    input_t input;
    if (peer->Admit(rbuf, channel, &input) < 0) return;
    std::lock_guard<std::mutex> lock(peer->mutex_);
    peer->inputs_.push_back(input.step);
  }

  static inline int count_ = 0;
  const std::string url_;
  const std::string prefix_;
  lcm::LCM lcm_;
  Signer signer_;
  ReplayWindow replay_;
  mutable std::mutex mutex_;
  std::vector<std::string> refused_;
  std::vector<int64_t> inputs_;
  std::atomic<bool> running_{true};
  std::thread thread_;
};

class ClientAuthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    key_file_ = ::testing::TempDir() + "contactsim-client-auth-" + std::to_string(::getpid()) + ".key";
    std::ofstream(key_file_) << testing::kTestKey << "\n";
  }
  void TearDown() override { std::remove(key_file_.c_str()); }
  std::string key_file_;
};

// Verifies that commands go out signed and signed replies and STATUS are read.
TEST_F(ClientAuthTest, SignedCommandsGetSignedReplies) {
  SigningPeer peer;
  Client client(peer.Options(key_file_));
  ASSERT_TRUE(client.good()) << client.error();
  EXPECT_TRUE(client.signs());
  const CommandResult result = client.Pause();
  EXPECT_TRUE(result.ok()) << result;
  status_t status{};
  status.version = "peer";
  peer.Publish("STATUS", status);
  EXPECT_TRUE(client.WaitForServer(kWait));
  EXPECT_TRUE(peer.refused().empty()) << peer.refused().front();
  EXPECT_EQ(client.auth_failures(), 0u);
}

// Verifies that unsigned server output is dropped and counted, and that the
// timeout says so.
TEST_F(ClientAuthTest, UnsignedServerOutputIsDroppedAndCounted) {
  SigningPeer peer;
  peer.sign = false;
  ClientOptions options = peer.Options(key_file_);
  options.reply_timeout = 500ms;
  Client client(options);
  const CommandResult result = client.Pause();
  EXPECT_EQ(result.code, ReplyCode::kTimeout);
  EXPECT_NE(result.message.find("failed their signature check"), std::string::npos) << result.message;
  EXPECT_GE(client.auth_failures(), 1u);
  EXPECT_EQ(client.last_auth_failure().rfind(client.Channel("REPLY") + ": unsigned:", 0), 0u)
      << client.last_auth_failure();
}

// Verifies that a client without a key sends unsigned commands and reads
// signed output (it strips the trailer).
TEST_F(ClientAuthTest, ClientWithoutKeyReadsSignedOutput) {
  SigningPeer peer;
  peer.require_signed = false;
  Client client(peer.Options(""));
  EXPECT_FALSE(client.signs());
  EXPECT_TRUE(client.Pause().ok());
  peer.PublishState(7);
  EXPECT_TRUE(client.WaitForState([](const state_t& s) { return s.step == 7; }, kWait));
}

// Verifies that lockstep inputs, sent directly and by the Controller, are
// signed.
TEST_F(ClientAuthTest, LockstepInputsAreSigned) {
  SigningPeer peer;
  Client client(peer.Options(key_file_));
  EXPECT_NE(client.SendInput(1, {}), 0);
  Controller controller(client, [](const state_t&) { return BodyInputs{{1, BodyWrench{}}}; });
  ASSERT_TRUE(controller.Start().ok());
  peer.PublishState(1);
  EXPECT_TRUE(controller.WaitForStep(1, kWait));
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (peer.inputs().size() < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(peer.inputs(), (std::vector<int64_t>{1, 2}));
  EXPECT_TRUE(peer.refused().empty()) << peer.refused().front();
}

// Verifies that a bad key file leaves the client unusable, saying why,
// and that nothing is sent.
TEST_F(ClientAuthTest, BadKeyFileLeavesTheClientUnusable) {
  SigningPeer peer;
  Client client(peer.Options("/nonexistent/contactsim.key"));
  EXPECT_FALSE(client.good());
  EXPECT_NE(client.error().find("\"/nonexistent/contactsim.key\""), std::string::npos) << client.error();
  const CommandResult result = client.Pause();
  EXPECT_EQ(result.code, ReplyCode::kTransport);
  EXPECT_EQ(result.message, client.error());
  EXPECT_EQ(client.SendInput(1, {}), 0);
}

}  // namespace
}  // namespace contactsim
