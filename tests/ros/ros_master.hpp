#pragma once
// A ROS master of a test's own (a free port on the loopback, its own ROS_HOME) and background
// processes killed with their process group: the fixture of the tests that run rownav's nodes
// against a real master (issue 15).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "common/cli_runner.hpp"

namespace rownav::test {

/// A TCP port nobody listens on now (the loopback).
inline int free_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(s);
  return ntohs(a.sin_port);
}

/// A shell command run in the background; killed (SIGINT, then SIGKILL) on destruction.
class Background {
 public:
  explicit Background(const std::string& cmd) {
    pid_ = ::fork();
    if (pid_ == 0) {
      ::setpgid(0, 0);
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~Background() { stop(); }
  /// SIGINT to the process group; the exit status (-1: killed after 5 s).
  int stop() {
    if (pid_ <= 0) return status_;
    ::kill(-pid_, SIGINT);
    for (int i = 0; i < 50; ++i) {
      int st = 0;
      if (::waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        return status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ::kill(-pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
    return status_ = -1;
  }
  /// Whether it still runs; once it has exited, stop() returns its exit status.
  bool running() {
    if (pid_ <= 0) return false;
    int st = 0;
    const pid_t r = ::waitpid(pid_, &st, WNOHANG);
    if (r != pid_) return r == 0;
    pid_ = -1;
    status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return false;
  }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
};

/// stdout of `cmd` run by /bin/sh.
inline std::string shell(const std::string& cmd) {
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  return out;
}

/// A master on a free port; `env_` prefixes a shell command with its ROS_MASTER_URI and homes.
/// Skips the test where rosmaster / rostopic are not installed.
class NodeAgainstAMaster : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::system("command -v rosmaster >/dev/null && command -v rostopic >/dev/null") != 0)
      GTEST_SKIP() << "rosmaster / rostopic not installed (scripts/install-deps installs them)";
    const std::string port = std::to_string(free_port());
    env_ = "ROS_MASTER_URI=http://127.0.0.1:" + port + " ROS_HOME='" + home_.path().string() +
           "' ROS_LOG_DIR='" + home_.path().string() + "' ";
    master_ = std::make_unique<Background>(env_ + "exec rosmaster --core -p " + port +
                                           " >/dev/null 2>&1");
    for (int i = 0; i < 50 && shell(env_ + "rostopic list 2>/dev/null").empty(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  TempDir home_{"roshome"};
  std::string env_;
  std::unique_ptr<Background> master_;
};

}  // namespace rownav::test
