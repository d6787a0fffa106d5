// waitForLink: wait until a node publishing `topic` will send its messages to this node.
//
// A ros::Subscriber counts a publisher as soon as it starts connecting, before the publisher has
// the connection: what the publisher sends in between is lost. A client that sends an input and
// waits for its answer must wait for the publisher's side, which this asks the publishing node for
// (the ROS slave API's getBusInfo lists its live outgoing connections).
#pragma once

#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <string>

namespace wheel_rail_contact_examples {

/// True once some publisher of `topic` lists a connection to this node, false after `timeout`.
inline bool waitForLink(const std::string& topic, double timeout) {
  const std::string resolved = ros::names::resolve(topic), me = ros::this_node::getName();
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && ros::WallTime::now() < end) {
    XmlRpc::XmlRpcValue args, state, payload;
    args[0] = me;
    if (ros::master::execute("getSystemState", args, state, payload, false))
      for (int t = 0; t < payload[0].size(); ++t) {  // payload[0]: [topic, [publisher nodes]]
        if (std::string(payload[0][t][0]) != resolved) continue;
        for (int n = 0; n < payload[0][t][1].size(); ++n) {
          XmlRpc::XmlRpcValue lookup, reply, uri, info, rows;
          lookup[0] = me;
          lookup[1] = payload[0][t][1][n];
          std::string host;
          uint32_t port = 0;
          if (!ros::master::execute("lookupNode", lookup, reply, uri, false) ||
              !ros::network::splitURI(uri, host, port))
            continue;
          XmlRpc::XmlRpcClient node(host.c_str(), static_cast<int>(port), "/");
          if (!node.execute("getBusInfo", args, info) || info.size() < 3) continue;
          rows = info[2];  // [id, destination node, direction, transport, topic, connected, ...]
          for (int r = 0; r < rows.size(); ++r)
            if (std::string(rows[r][1]) == me && std::string(rows[r][2]) == "o" &&
                std::string(rows[r][4]) == resolved)
              return true;
        }
      }
    ros::WallDuration(0.01).sleep();  // poll the graph again
  }
  return false;
}

}  // namespace wheel_rail_contact_examples
