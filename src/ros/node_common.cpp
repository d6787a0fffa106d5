#include "node_common.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "ros_conversions.hpp"

namespace wheel_rail_contact {

namespace {

bool validName(const std::string& n) {
  if (n.empty() || !std::isalpha(static_cast<unsigned char>(n[0]))) return false;
  for (char ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') return false;
  return true;
}

}  // namespace

std::string numberText(double v) {
  char t[64];
  std::snprintf(t, sizeof t, "%.17g", v);
  return t;
}

double toNumber(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double d = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    throw std::invalid_argument(name + ": expected a number, got '" + text + "'");
  return d;
}

std::vector<std::string> readNameList(const ros::NodeHandle& pnh, const std::string& key,
                                      const std::string& what) {
  XmlRpc::XmlRpcValue list;
  if (!pnh.getParam(key, list))
    throw std::invalid_argument(key + ": not set (a list of " + what + " names)");
  if (list.getType() != XmlRpc::XmlRpcValue::TypeArray || list.size() == 0)
    throw std::invalid_argument(key + ": expected a non-empty list of names, got " + list.toXml());
  std::vector<std::string> names;
  for (int i = 0; i < list.size(); ++i) {
    if (list[i].getType() != XmlRpc::XmlRpcValue::TypeString)
      throw std::invalid_argument(key + ": entry " + std::to_string(i) +
                                  " is not a name: " + list[i].toXml());
    const std::string n = static_cast<std::string>(list[i]);
    if (!validName(n))
      throw std::invalid_argument(key + ": '" + n +
                                  "' is not a name (a letter, then letters, digits, _)");
    names.push_back(n);
  }
  return names;
}

int readCount(const ros::NodeHandle& pnh, const char* name, int value) {
  XmlRpc::XmlRpcValue x;
  if (!pnh.getParam(name, x)) return value;
  const double d = toNumber(name, parameterText(name, x));
  if (!(d >= 1.0 && d <= 1e6) || d != static_cast<int>(d))
    throw std::invalid_argument(std::string(name) + ": must be an integer in [1, 1000000], got " +
                                numberText(d));
  return static_cast<int>(d);
}

double readDiagnosticPeriod(const ros::NodeHandle& pnh, double value) {
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam("diagnostic_period", v))
    value = toNumber("diagnostic_period", parameterText("diagnostic_period", v));
  if (!(value > 0.0 && value <= 86400.0))
    throw std::invalid_argument("diagnostic_period: must be in (0, 86400] s, got " +
                                numberText(value));
  return value;
}

std::string readFramePrefix(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam("frame_prefix", v)) return parameterText("frame_prefix", v);
  std::string prefix;
  for (char ch : nh.getNamespace()) prefix += ch == '/' ? '_' : ch;
  while (!prefix.empty() && prefix[0] == '_') prefix.erase(0, 1);
  if (!prefix.empty()) prefix += '_';
  return prefix;
}

void logIgnoredParameters(const char* node, const std::string& ns,
                          const std::set<std::string>& ignored) {
  if (ignored.empty()) return;
  std::string unused;
  for (const auto& k : ignored) unused += " " + k;
  ROS_INFO("%s %s: contact_node parameters not used here:%s", node, ns.c_str(), unused.c_str());
}

void LostInputs::see(const std::string& publisher, uint32_t seq, const std::string& ns,
                     const std::string& topic, int queueSize) {
  auto seen = lastSeq_.find(publisher);
  if (seen != lastSeq_.end() && seq > seen->second + 1) {
    lost_ += seq - seen->second - 1;
    ROS_WARN_THROTTLE(1.0, "%s: %lu %s messages lost before the node (queue_size %d)", ns.c_str(),
                      static_cast<unsigned long>(lost_), topic.c_str(), queueSize);
  }
  lastSeq_[publisher] = seq;
}

void NodeDiagnostics::start(ros::NodeHandle& nh, const ros::NodeHandle& pnh, double period,
                            std::mutex* mutex,
                            const std::function<void(diagnostic_updater::Updater&)>& addTasks) {
  updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh);
  updater_->setHardwareID("wheel_rail_contact" + nh.getNamespace());
  addTasks(*updater_);
  lastTime_ = ros::WallTime::now();
  timer_ = nh.createWallTimer(ros::WallDuration(period), [this, mutex](const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(*mutex);
    updater_->force_update();
  });
}

double NodeDiagnostics::summarize(diagnostic_updater::DiagnosticStatusWrapper& stat, uint64_t ticks,
                                  uint64_t unknown, uint64_t lost, const std::string& topic,
                                  const std::string& items) {
  const ros::WallTime now = ros::WallTime::now();
  const double span = (now - lastTime_).toSec();
  const double rate = span > 0.0 ? static_cast<double>(ticks - lastTicks_) / span : 0.0;
  if (lost > lastLost_)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 topic + " messages lost before the node: raise queue_size");
  else if (unknown > lastUnknown_)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "inputs name unknown " + items);
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  lastTicks_ = ticks;
  lastUnknown_ = unknown;
  lastLost_ = lost;
  lastTime_ = now;
  return rate;
}

}  // namespace wheel_rail_contact
