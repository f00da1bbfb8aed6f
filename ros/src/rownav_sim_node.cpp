// rownav_sim_node: rownav's simulator as a ROS 1 node (docs/ros.md).
#include <ros/ros.h>

#include <exception>
#include <iostream>

#include "rownav_ros/sim_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "rownav_sim_node");
  try {
    rownav::ros_bridge::SimNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    return node.run();
  } catch (const std::exception& e) {
    ROS_FATAL("rownav_sim_node: %s", e.what());
    std::cerr << "rownav_sim_node: error: " << e.what() << std::endl;
    return 2;
  }
}
