// rownav_node: map-free LiDAR row navigation for ROS 1 (docs/ros.md).
#include <ros/ros.h>

#include <exception>
#include <iostream>

#include "rownav_ros/ros_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "rownav_node");
  try {
    rownav::ros_bridge::RosNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    // One line on the terminal as well: ROS_FATAL goes to rosout, which a failed start may not
    // reach, and a user running the node by hand must see why it stopped.
    ROS_FATAL("rownav_node: %s", e.what());
    std::cerr << "rownav_node: error: " << e.what() << std::endl;
    return 2;
  }
  return 0;
}
