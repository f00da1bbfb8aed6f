// rownav_node against a running ROS master of the test's own (a free port on the loopback):
// it starts with list parameters given on the command line, publishes its state and
// diagnostics, and stops cleanly; a bad parameter is one line on the terminal (issue 15).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "common/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

int free_port() {
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
  bool running() const { return pid_ > 0 && ::waitpid(pid_, nullptr, WNOHANG) == 0; }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
};

std::string shell(const std::string& cmd) {
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  return out;
}

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
  rownav::test::TempDir home_{"roshome"};
  std::string env_;
  std::unique_ptr<Background> master_;
};

TEST_F(NodeAgainstAMaster, StartsWithCommandLineListsPublishesItsStateAndStopsCleanly) {
  ASSERT_FALSE(shell(env_ + "rostopic list 2>/dev/null").empty()) << "no master";
  const std::string log = (home_.path() / "node.log").string();
  Background node(env_ + "exec '" ROWNAV_NODE_BINARY "' '_lidar_mount:=[0.3,0,0.8,0,0,0]' "
                  "_corridor_count:=5 _robot:=" ROWNAV_SOURCE_DIR "/config/robots/skid_steer.yaml "
                  "> '" + log + "' 2>&1");
  const std::string state =
      shell(env_ + "timeout 15 rostopic echo -n 1 /rownav_node/state 2>/dev/null");
  EXPECT_NE(state.find("in_row"), std::string::npos) << state << rownav::test::read_file(log);
  const std::string diag = shell(env_ + "timeout 15 rostopic echo -n 1 /diagnostics 2>/dev/null");
  EXPECT_NE(diag.find("rownav_node"), std::string::npos) << diag;
  EXPECT_NE(diag.find("lidar_age_s"), std::string::npos) << diag;
  EXPECT_TRUE(node.running()) << rownav::test::read_file(log);
  EXPECT_EQ(node.stop(), 0) << rownav::test::read_file(log);
}

TEST_F(NodeAgainstAMaster, ABadParameterIsOneLineOnTheTerminalAndExitStatus2) {
  ASSERT_FALSE(shell(env_ + "rostopic list 2>/dev/null").empty()) << "no master";
  const std::string out = shell(env_ + "timeout 15 '" ROWNAV_NODE_BINARY
                                "' _corridor_count:=five 2>&1; echo \"exit=$?\"");
  EXPECT_NE(out.find("rownav_node: error: "), std::string::npos) << out;
  EXPECT_NE(out.find("corridor_count"), std::string::npos) << out;
  EXPECT_NE(out.find("exit=2"), std::string::npos) << out;
}

}  // namespace
