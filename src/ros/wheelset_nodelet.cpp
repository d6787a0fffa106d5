// wheelset_nodelet: wheelset_node as a nodelet, for a simulator that loads it into its own nodelet
// manager (zero-copy WheelsetInput and WheelsetForces). Same parameters, topics and services.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>
#include <stdexcept>

#include "wheelset_node.hpp"

namespace wheel_rail_contact {

class WheelsetNodelet : public nodelet::Nodelet {
  void onInit() override {
    node_ = std::make_unique<WheelsetNode>(getNodeHandle(), getPrivateNodeHandle());
    // ROS_FATAL has named the parameter; throwing makes the manager refuse the load.
    if (!node_->readParameters()) throw std::invalid_argument(getName() + ": invalid parameter");
    node_->start();
  }
  std::unique_ptr<WheelsetNode> node_;
};

}  // namespace wheel_rail_contact

PLUGINLIB_EXPORT_CLASS(wheel_rail_contact::WheelsetNodelet, nodelet::Nodelet)
