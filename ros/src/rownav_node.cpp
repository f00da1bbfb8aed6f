// rownav_node: map-free LiDAR row navigation for ROS 1 (docs/ros.md).
#include <ros/ros.h>

#include <exception>

#include "rownav_ros/ros_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "rownav_node");
  try {
    rownav::ros_bridge::RosNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("rownav_node: %s", e.what());
    return 1;
  }
  return 0;
}
