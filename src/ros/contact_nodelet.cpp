// contact_nodelet: contact_node as a nodelet, for a simulator that loads it into its own nodelet
// manager (zero-copy messages). Same parameters, topics and services as contact_node.
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>
#include <stdexcept>

#include "contact_node.hpp"

namespace wheel_rail_contact {

class ContactNodelet : public nodelet::Nodelet {
  void onInit() override {
    node_ = std::make_unique<ContactNode>(getNodeHandle(), getPrivateNodeHandle());
    // ROS_FATAL has named the parameter; throwing makes the manager refuse the load.
    if (!node_->readParameters()) throw std::invalid_argument(getName() + ": invalid parameter");
    node_->start();
  }
  std::unique_ptr<ContactNode> node_;
};

}  // namespace wheel_rail_contact

PLUGINLIB_EXPORT_CLASS(wheel_rail_contact::ContactNodelet, nodelet::Nodelet)
