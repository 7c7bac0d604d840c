// Runs the real contactsim-server as a child process for integration tests.
//
// Each server gets its own multicast port (7800-8799) and channel prefix, so
// tests that ctest runs in parallel never hear each other: even when two
// ports collide, the prefixes differ. Header-only because the test glob
// (tests/CMakeLists.txt) compiles only *_test.cpp files.
#pragma once

#include <stdlib.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "contactsim/client.h"

extern char** environ;

namespace contactsim::testing {

// Generous: two cores are shared by parallel ctest runs and other builds.
constexpr std::chrono::milliseconds kStartTimeout{15000};
constexpr std::chrono::milliseconds kReplyTimeout{5000};
constexpr std::chrono::milliseconds kExitTimeout{10000};

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A temporary file (name ends in `suffix`) removed when this goes away.
class TempFile {
 public:
  TempFile(const std::string& stem, const std::string& suffix,
           const std::string& content) {
    std::string name = "/tmp/" + stem + "-XXXXXX" + suffix;
    const int fd = ::mkstemps(name.data(), static_cast<int>(suffix.size()));
    if (fd >= 0) {
      path_ = name;
      ::close(fd);
      std::ofstream(path_) << content;
    }
  }
  ~TempFile() {
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Starts argv[0] with stdout and stderr into `log_path`; -1 on failure.
inline pid_t Spawn(const std::vector<std::string>& args,
                   const std::string& log_path) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null",
                                   O_RDONLY, 0);
  pid_t pid = -1;
  const int error =
      posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// waitpid with a deadline; the raw wait status, or -1 if still running.
inline int WaitFor(pid_t pid, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;
    if (std::chrono::steady_clock::now() > deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// A program's exit code (-1: did not exit normally in time) and its output.
struct ProcessOutput {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

inline ProcessOutput RunProcess(const std::vector<std::string>& args,
                                std::chrono::milliseconds timeout) {
  TempFile log("contactsim-it-run", ".log", "");
  ProcessOutput result;
  const pid_t pid = Spawn(args, log.path());
  if (pid < 0) {
    result.output = "cannot start " + args.front();
    return result;
  }
  const int status = WaitFor(pid, timeout);
  if (status == -1) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  } else if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  }
  result.output = ReadFile(log.path());
  return result;
}

// One contactsim-server child process with its own port and prefix.
class ServerProcess {
 public:
  ServerProcess()
      : scene_("contactsim-it-scene", ".pbtxt", "gravity { z: -9.81 }\n"),
        log_("contactsim-it-server", ".log", "") {
    // Distinct per process (pid) and per server within it (counter).
    static std::atomic<int> servers{0};
    const int n = servers.fetch_add(1);
    const int port = 7800 + static_cast<int>((::getpid() * 7L + n) % 1000);
    url_ = "udpm://239.255.76.67:" + std::to_string(port) +
           "?ttl=0&recv_buf_size=8388608";
    prefix_ = "IT" + std::to_string(::getpid()) + "_" + std::to_string(n);
  }
  ~ServerProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  bool Start() {
    pid_ = Spawn({std::string(CONTACTSIM_BIN_DIR) + "/contactsim-server",
                  "--config", std::string(CONTACTSIM_SOURCE_DIR) + "/config/server.pbtxt",
                  "--scene", scene_.path(), "--lcm-url", url_, "--prefix", prefix_,
                  "--mode", "free_run", "--paused", "--no-live-line"},
                 log_.path());
    return pid_ > 0;
  }

  // SIGINT, then the raw wait status (-1: it had to be killed).
  int Stop() {
    if (pid_ <= 0) return -1;
    ::kill(pid_, SIGINT);
    int status = WaitFor(pid_, kExitTimeout);
    if (status == -1) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    pid_ = -1;
    return status;
  }

  // A client of this server, subscribed before the server starts so that
  // it also hears the STATUS and STATE published at start.
  std::unique_ptr<Client> NewClient() const {
    ClientOptions options;
    options.url = url_;
    options.prefix = prefix_;
    options.reply_timeout = kReplyTimeout;
    return std::make_unique<Client>(options);
  }

  bool running() const { return pid_ > 0; }
  const std::string& url() const { return url_; }
  const std::string& prefix() const { return prefix_; }
  std::string Log() const { return ReadFile(log_.path()); }

 private:
  TempFile scene_;
  TempFile log_;
  std::string url_;
  std::string prefix_;
  pid_t pid_ = -1;
};

// Starts one server with an empty scene and a client of it; on teardown the
// server must shut down cleanly on SIGINT.
class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // these servers have no key: a key exported in the developer's shell
    // would make the clients sign and drop the servers' unsigned output
    ::unsetenv("CONTACTSIM_AUTH_KEY_FILE");
    StartServer(server_, client_);
  }

  void TearDown() override { StopServer(server_, client_); }

  static void StartServer(ServerProcess& server, std::unique_ptr<Client>& client) {
    client = server.NewClient();
    ASSERT_TRUE(client->good()) << "LCM unusable with " << server.url();
    ASSERT_TRUE(server.Start()) << "cannot start " CONTACTSIM_BIN_DIR "/contactsim-server";
    ASSERT_TRUE(client->WaitForServer(kStartTimeout))
        << "no STATUS on " << client->Channel("STATUS") << "; server log:\n"
        << server.Log();
  }

  void StopServer(ServerProcess& server, std::unique_ptr<Client>& client) {
    client.reset();
    if (!server.running()) return;  // SetUp failed before starting it
    const bool had_failure = HasFailure();
    const int status = server.Stop();
    EXPECT_TRUE(status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << "server did not exit cleanly on SIGINT (wait status " << status
        << "); log:\n" << server.Log();
    if (had_failure) {
      std::cerr << "server log (" << server.prefix() << "):\n" << server.Log();
    }
  }

  ServerProcess server_;
  std::unique_ptr<Client> client_;
};

}  // namespace contactsim::testing
