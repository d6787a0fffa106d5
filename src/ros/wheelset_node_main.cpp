// wheelset_node: every wheelset of a vehicle on real profiles in one node (see wheelset_node.hpp
// and doc/wheelset_interface.md).
#include <ros/ros.h>

#include "wheelset_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "wheelset_node");
  wheel_rail_contact::WheelsetNode node{ros::NodeHandle(), ros::NodeHandle("~")};
  if (!node.readParameters()) return 1;  // ROS_FATAL has named the parameter
  node.start();
  ros::spin();
  return 0;
}
