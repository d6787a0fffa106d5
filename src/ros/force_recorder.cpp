// force_recorder: writes every ContactState of one or more contacts to CSV, one file per contact,
// then exits (launch it with required="true" to end a demo). Private parameters: contacts (list of
// namespaces relative to this node's, default [""]), output_dir (default "."), idle_timeout (wall s
// without a message after the first one, default 2), max_wait (wall s for the first message,
// default 60), expected (messages per contact after which it stops at once; 0 = idle timeout).
// Columns: stamp,t,fx,fy,mz,fz,a,b,adhesion_fraction,force_magnitude,force_angle_deg,status,dt,
// solver_time,message (t from the first stamp of that contact; angle = atan2(fy, fx)).
#include <ros/ros.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include "wheel_rail_contact/ContactState.h"

namespace {

struct Contact {
  std::string ns, file;
  std::unique_ptr<std::ofstream> out;
  ros::Subscriber sub;
  size_t count = 0;
  ros::Time first;
};

std::string fileName(std::string ns) {
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  for (auto& ch : ns)
    if (ch == '/') ch = '_';
  return (ns.empty() ? std::string("contact") : ns) + "_forces.csv";
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "force_recorder");
  ros::NodeHandle nh, pnh("~");
  std::vector<std::string> names{""};
  std::string dir = ".";
  double idleTimeout = 2.0, maxWait = 60.0;
  int expected = 0;
  pnh.param("contacts", names, names);
  pnh.param("output_dir", dir, dir);
  pnh.param("idle_timeout", idleTimeout, idleTimeout);
  pnh.param("max_wait", maxWait, maxWait);
  pnh.param("expected", expected, expected);

  ros::WallTime last = ros::WallTime::now();
  bool any = false;
  std::vector<std::unique_ptr<Contact>> contacts;
  for (const auto& name : names) {
    auto c = std::make_unique<Contact>();
    c->ns = name;
    c->file = dir + "/" + fileName(name.empty() ? nh.getNamespace() : name);
    c->out = std::make_unique<std::ofstream>(c->file);
    if (!*c->out) {
      ROS_FATAL("force_recorder: output_dir: cannot write '%s'", c->file.c_str());
      return 1;
    }
    *c->out << "stamp,t,fx,fy,mz,fz,a,b,adhesion_fraction,force_magnitude,force_angle_deg,status,"
               "dt,solver_time,message\n";
    Contact* raw = c.get();
    const std::string topic = name.empty() ? "contact_state" : name + "/contact_state";
    c->sub = nh.subscribe<wheel_rail_contact::ContactState>(
        topic, 10000, [raw, &last, &any](const wheel_rail_contact::ContactState::ConstPtr& m) {
          if (raw->count == 0) raw->first = m->header.stamp;
          ++raw->count;
          any = true;
          last = ros::WallTime::now();
          char line[512];
          std::snprintf(line, sizeof line,
                        "%.9f,%.9f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%u,%.9g,"
                        "%.6g,",
                        m->header.stamp.toSec(), (m->header.stamp - raw->first).toSec(), m->fx,
                        m->fy, m->mz, m->fz, m->a, m->b, m->adhesion_fraction,
                        std::hypot(m->fx, m->fy), std::atan2(m->fy, m->fx) * 180.0 / M_PI,
                        static_cast<unsigned>(m->status), m->dt, m->solver_time);
          *raw->out << line << '"' << m->message << '"' << '\n';
        });
    contacts.push_back(std::move(c));
  }
  const ros::WallTime start = ros::WallTime::now();
  ros::WallRate poll(200);
  while (ros::ok()) {
    ros::spinOnce();
    const ros::WallTime now = ros::WallTime::now();
    bool done = expected > 0;
    for (const auto& c : contacts) done = done && c->count >= static_cast<size_t>(expected);
    if (done || (any && (now - last).toSec() > idleTimeout)) break;
    if (!any && (now - start).toSec() > maxWait) {
      ROS_ERROR("force_recorder: no contact_state within max_wait = %g s", maxWait);
      return 1;
    }
    poll.sleep();
  }
  for (const auto& c : contacts) {
    c->out->close();
    ROS_INFO("force_recorder: %zu steps of %s -> %s", c->count,
             c->ns.empty() ? nh.getNamespace().c_str() : c->ns.c_str(), c->file.c_str());
  }
  return 0;
}
