// rownav_node against a running ROS master of the test's own (a free port on the loopback):
// it starts with list parameters given on the command line, publishes its state and
// diagnostics, and stops cleanly; a bad parameter is one line on the terminal; its ~pause /
// ~start / ~stop services, called through ros::ServiceClient while rownav_sim_node drives it,
// zero cmd_vel and resume, and refuse to resume once the robot was pushed into another corridor
// during the pause (issue 15).
#include <geometry_msgs/Pose2D.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ros/ros_master.hpp"

namespace {

using rownav::test::Background;
using rownav::test::NodeAgainstAMaster;
using rownav::test::read_file;
using rownav::test::shell;
using Clock = std::chrono::steady_clock;

TEST_F(NodeAgainstAMaster, StartsWithCommandLineListsPublishesItsStateAndStopsCleanly) {
  ASSERT_FALSE(shell(env_ + "rostopic list 2>/dev/null").empty()) << "no master";
  const std::string log = (home_.path() / "node.log").string();
  Background node(env_ +
                  "exec '" ROWNAV_NODE_BINARY
                  "' '_lidar_mount:=[0.3,0,0.8,0,0,0]' "
                  "_corridor_count:=5 _robot:=" ROWNAV_SOURCE_DIR
                  "/config/robots/skid_steer.yaml "
                  "> '" +
                  log + "' 2>&1");
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

/// cmd_vel and ~state as this process receives them (wall-clock arrival times).
class Listener {
 public:
  explicit Listener(ros::NodeHandle& nh)
      : cmd_(nh.subscribe("/cmd_vel", 100, &Listener::on_cmd, this)),
        state_(nh.subscribe("/rownav_node/state", 10, &Listener::on_state, this)) {}
  /// Waits up to `timeout` for a command with v > `v`; true when one came.
  bool wait_driving(double v, std::chrono::seconds timeout) {
    const auto end = Clock::now() + timeout;
    for (auto from = Clock::now(); Clock::now() < end;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      for (const auto& c : since(from))
        if (c.v > v) return true;
    }
    return false;
  }
  struct Cmd {
    Clock::time_point at;
    double v, vy, omega;
  };
  std::vector<Cmd> since(Clock::time_point t) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Cmd> out;
    for (const auto& c : cmds_)
      if (c.at >= t) out.push_back(c);
    return out;
  }
  std::string state() {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_text_;
  }

 private:
  void on_cmd(const geometry_msgs::Twist::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    cmds_.push_back({Clock::now(), m->linear.x, m->linear.y, m->angular.z});
  }
  void on_state(const std_msgs::String::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    state_text_ = m->data;
  }
  std::mutex mutex_;
  std::vector<Cmd> cmds_;
  std::string state_text_;
  ros::Subscriber cmd_, state_;
};

/// Every command received from `from` (`grace` after a service answer, for messages already
/// on the wire) for `span` is exactly zero; returns how many there were.
int zero_commands(Listener& l, Clock::time_point from, std::chrono::milliseconds span) {
  std::this_thread::sleep_for(from + span - Clock::now());
  int n = 0;
  for (const auto& c : l.since(from)) {
    ++n;
    EXPECT_EQ(c.v, 0.0);
    EXPECT_EQ(c.vy, 0.0);
    EXPECT_EQ(c.omega, 0.0);
  }
  return n;
}

/// Prints the files on destruction when the test has failed (an ASSERT returns early too).
struct PrintOnFailure {
  std::vector<std::string> files;
  ~PrintOnFailure() {
    if (::testing::Test::HasFailure())
      for (const auto& f : files) std::cerr << f << ":\n" << read_file(f);
  }
};

std_srvs::Trigger call(const std::string& name) {
  std_srvs::Trigger t;
  EXPECT_TRUE(ros::service::call("/rownav_node/" + name, t)) << name;
  return t;
}

TEST_F(NodeAgainstAMaster, PauseStartStopServicesZeroTheCommandAndResume) {
  ASSERT_FALSE(shell(env_ + "rostopic list 2>/dev/null").empty()) << "no master";
  const auto dir = home_.path();
  const std::string config = ROWNAV_SOURCE_DIR "/config";
  std::ofstream(dir / "field.yaml") << "kind: vineyard\nname: ros_pause\nseed: 3\nvineyard:\n"
                                       "  rows: 4\n  row_length: 15.0\n  row_spacing: 1.8\n";
  const std::string robot = config + "/robots/skid_steer.yaml";
  const std::string mission = config + "/missions/two_corridors.yaml";
  const std::string sim_log = (dir / "sim.log").string(), log = (dir / "node.log").string();
  const PrintOnFailure print{{log, sim_log}};
  // Line-buffered: the test reads the sim node's log while it runs (the carry's line).
  Background sim(env_ +
                 "ROSCONSOLE_STDOUT_LINE_BUFFERED=1 exec '" ROWNAV_SIM_NODE_BINARY "' _field:=" +
                 (dir / "field.yaml").string() + " _robot:=" + robot + " _sensors:=" + config +
                 "/sensors/os1_16.yaml _mission:=" + mission +
                 " _rate_factor:=1.0 _time_limit:=60 > '" + sim_log + "' 2>&1");
  for (int i = 0;
       i < 100 && shell(env_ + "rostopic list 2>/dev/null").find("/clock") == std::string::npos;
       ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  Background node(env_ + "exec '" ROWNAV_NODE_BINARY "' _robot:=" + robot +
                  " _detect_config:=" + config + "/detect/vineyard.yaml _mission:=" + mission +
                  " _corridor_count:=3 > '" + log + "' 2>&1");
  // This process as a ROS client of the same master.
  const std::string uri = env_.substr(15, env_.find(' ') - 15);  // "ROS_MASTER_URI=<uri> ..."
  ros::init(ros::M_string{{"__master", uri}}, "rownav_service_test",
            ros::init_options::AnonymousName | ros::init_options::NoSigintHandler |
                ros::init_options::NoRosout);
  ros::NodeHandle nh;
  Listener listener(nh);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ASSERT_TRUE(ros::service::waitForService("/rownav_node/stop", ros::Duration(15.0)));
  ASSERT_TRUE(listener.wait_driving(0.1, std::chrono::seconds(10))) << read_file(sim_log);
  constexpr auto kGrace = std::chrono::milliseconds(200), kHold = std::chrono::milliseconds(1500);

  const std_srvs::Trigger pause = call("pause");
  EXPECT_TRUE(pause.response.success);
  EXPECT_EQ(pause.response.message, "paused in in_row: command zero, ~start resumes");
  EXPECT_GT(zero_commands(listener, Clock::now() + kGrace, kHold), 10);  // 20 Hz ticks at least
  EXPECT_EQ(listener.state(), "paused");

  const std_srvs::Trigger start = call("start");
  EXPECT_TRUE(start.response.success);
  EXPECT_EQ(start.response.message, "resumed in in_row");
  EXPECT_TRUE(listener.wait_driving(0.1, std::chrono::seconds(3)));  // no safe stop after it
  EXPECT_EQ(listener.state(), "in_row");

  const std_srvs::Trigger stop = call("stop");
  EXPECT_TRUE(stop.response.success);
  EXPECT_NE(stop.response.message.find("mission stopped"), std::string::npos);
  EXPECT_GT(zero_commands(listener, Clock::now() + kGrace, std::chrono::milliseconds(1000)), 5);
  EXPECT_EQ(listener.state(), "stopped");
  const std_srvs::Trigger again = call("start");
  EXPECT_TRUE(again.response.success);
  EXPECT_EQ(again.response.message,
            "new mission started (the last one stopped in in_row), 2 corridors from corridor 0");
  EXPECT_TRUE(listener.wait_driving(0.1, std::chrono::seconds(3)));  // a new mission, in place
  EXPECT_EQ(listener.state(), "in_row");

  // Paused again, the robot is pushed one spacing to the left, across the row into corridor 1
  // (the sim node's ~carry, 0.5 m/s; its wheels do not turn): the resume is refused, the pause
  // stays (the same guard as RowNavCore's unit test, here through the real transport).
  EXPECT_TRUE(call("pause").response.success);
  ros::Publisher carry = nh.advertise<geometry_msgs::Pose2D>("/rownav_sim_node/carry", 1, true);
  geometry_msgs::Pose2D push;
  push.y = 1.8;
  carry.publish(push);  // latched: delivered once the sim node is connected
  std::this_thread::sleep_for(std::chrono::milliseconds(4500));  // 3.6 s at 0.5 m/s, and frames
  const std_srvs::Trigger refused = call("start");
  EXPECT_FALSE(refused.response.success);
  EXPECT_EQ(refused.response.message.rfind("not resumed: ", 0), 0u) << refused.response.message;
  EXPECT_GT(zero_commands(listener, Clock::now() + kGrace, std::chrono::milliseconds(1000)), 5);
  EXPECT_EQ(listener.state(), "paused");
  EXPECT_NE(read_file(sim_log).find("carrying the robot by (0.00 m, 1.80 m"), std::string::npos);
  spinner.stop();
  ros::shutdown();
  EXPECT_TRUE(node.running());
  EXPECT_EQ(node.stop(), 0);
}

}  // namespace
