// contact_node: one wheel-rail contact as a ROS node (contact_node.hpp; doc/ros_interface.md).
#include <ros/ros.h>

#include "contact_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "contact_node");
  wheel_rail_contact::ContactNode node{ros::NodeHandle(), ros::NodeHandle("~")};
  if (!node.readParameters()) return 1;  // ROS_FATAL has named the parameter
  node.start();
  ros::spin();
  return 0;
}
