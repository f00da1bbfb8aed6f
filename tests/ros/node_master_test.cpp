// rownav_node against a running ROS master of the test's own (a free port on the loopback):
// it starts with list parameters given on the command line, publishes its state and
// diagnostics, and stops cleanly; a bad parameter is one line on the terminal (issue 15).
#include "ros/ros_master.hpp"

namespace {

using rownav::test::Background;
using rownav::test::NodeAgainstAMaster;
using rownav::test::shell;

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
