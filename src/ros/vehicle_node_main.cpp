// vehicle_node: all wheel-rail contacts of a vehicle in one node (see vehicle_node.hpp and
// doc/vehicle_interface.md).
#include <ros/ros.h>

#include "vehicle_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "vehicle_node");
  wheel_rail_contact::VehicleNode node{ros::NodeHandle(), ros::NodeHandle("~")};
  if (!node.readParameters()) return 1;  // ROS_FATAL has named the parameter
  node.start();
  ros::spin();
  return 0;
}
