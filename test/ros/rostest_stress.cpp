// rostest (stress.test): eight contact_nodes (nss, fixed and adaptive mesh) fed at `rate` Hz for
// `duration` s of sim time with a seeded random scene and injected faults: bursts, duplicated
// messages, out-of-order stamps, swapped pairs, non-finite inputs, load silences and resets.
//
// Pacing: the test publishes /clock and the inputs of one tick (or of a whole burst), then waits
// for every output before the next tick, so the run is as fast as the machine allows and never
// drops anything on a loaded one. Loads and creepages come on separate connections, so the order
// in which a node sees them is not fixed: the load a step used is read back from contact_state's
// fz (it must be this tick's or the previous tick's load, else the tick counts as perturbed).
//
// Asserted, per contact:
//  - every creepage message gives exactly one creep_force and one contact_state, in order, stamp
//    copied, finite, both equal; rejected ones have status rejected and are counted by cause in
//    the diagnostics, which also count every message, the resets and the stale-load steps;
//  - "mirror": a core model fed exactly what the node says it stepped (dt, fz of each output) gives
//    bit-identical outputs: no fault corrupts the state beyond what the rules say;
//  - "clean": a core model fed the fault-free scene equals the node bit for bit until the first
//    perturbed tick, and to `tolerance` (of mu fz0) once `settle` patch lengths have rolled by
//    after every perturbed tick,
//    once the history has flushed through the patch; and differs right after the faults (the
//    comparison can fail);
//  - the node processes' VmRSS late in the run is within `rss_tolerance_kb` of the RSS early on.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/callback_queue.h>
#include <ros/master.h>
#include <ros/network.h>
#include <rosgraph_msgs/Clock.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <algorithm>
#include <deque>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "../../src/ros/contact_stepper.hpp"
#include "rostest_helpers.hpp"
#include "wheel_rail_contact/contact_model.hpp"

using namespace wrc_test;
using wheel_rail_contact::ContactParameters;
using wheel_rail_contact::StepOutput;

namespace {

const char* kContacts[] = {"bogie1/wheelset1/left", "bogie1/wheelset1/right",
                           "bogie1/wheelset2/left", "bogie1/wheelset2/right",
                           "bogie2/wheelset1/left", "bogie2/wheelset1/right",
                           "bogie2/wheelset2/left", "bogie2/wheelset2/right"};
const int64_t kT0Ns = 100000000000LL;  // sim time of tick 0: 100 s

struct Options {
  double duration = 60.0;  // sim seconds
  double rate = 2000.0;    // ticks per sim second
  int seed = 20261122;
  double settle = 10.0;     // patch lengths 2 a0 rolled after a perturbed tick before "clean" is
                            // compared again (the history has left the patch)
  double tolerance = 1e-5;  // of mu fz0 (forces) and mu fz0 a0 (moment); measured 5.5e-7
  double rssToleranceKb = 2048.0;  // late - early VmRSS per node
  int64_t ticks() const { return static_cast<int64_t>(duration * rate + 0.5); }
  int64_t tickNs() const { return static_cast<int64_t>(1e9 / rate + 0.5); }
};

struct Inputs {
  double V, xi, eta, phi, fz;
};

/// mean + three sinusoids of seeded amplitude, frequency (up to fmax) and phase; the amplitudes
/// add up to `amplitude` on average, 1.5 `amplitude` at most.
class Signal {
 public:
  Signal(std::mt19937_64& rng, double mean, double amplitude, double fmax) : mean_(mean) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (auto& w : waves_)
      w = {amplitude / 3.0 * (0.5 + u(rng)), 2 * M_PI * fmax * (0.03 + u(rng)), 2 * M_PI * u(rng)};
  }
  double at(double t) const {
    double v = mean_;
    for (const auto& w : waves_) v += w.a * std::sin(w.omega * t + w.phase);
    return v;
  }

 private:
  struct Wave {
    double a, omega, phase;
  };
  double mean_;
  Wave waves_[3];
};

/// A contact's scene: slow rolling (V 0.5-3.5 m/s: the 12 mm patch takes 7-48 ticks to pass, so
/// the history matters), partial slip, load fz0 +- 37.5 % at most (the fixed mesh covers 1.5 fz0).
struct Scene {
  Scene(std::mt19937_64& rng, const ContactParameters& p)
      : V(rng, 2.0, 1.0, 2.0),
        xi(rng, 0.0, 2.5e-3, 8.0),
        eta(rng, 0.0, 1.5e-3, 8.0),
        phi(rng, 0.0, 0.5, 8.0),
        fz(rng, p.fz0, 0.25 * p.fz0, 30.0) {}
  Inputs at(double t) const { return {V.at(t), xi.at(t), eta.at(t), phi.at(t), fz.at(t)}; }
  Signal V, xi, eta, phi, fz;
};

/// The faults of one contact, by tick.
struct FaultPlan {
  std::set<int64_t> duplicate, old, nonFinite, swap, reset;
  std::vector<std::pair<int64_t, int64_t>> silent;  // [from, to): no normal_load
  bool silentAt(int64_t k) const {
    for (const auto& s : silent)
      if (k >= s.first && k < s.second) return true;
    return false;
  }
};

enum class Kind { kCanonical, kDuplicate, kOld, kNonFinite };

struct Sent {
  int64_t stampNs, tick;
  Inputs in;
  Kind kind;
  bool overtaken = false;  // canonical, sent after the next tick's (a swapped pair)
  std::vector<double>
      allowedFz;  // canonical: the loads it may have used (this tick's, last one's)  // canonical:
                  // the loads it may have used (this tick's, last one's)
};

/// Counts and the first few failures, to assert once at the end (not a million EXPECTs).
struct Tally {
  uint64_t creepages = 0, loads = 0, states = 0, forces = 0, rejected = 0, duplicate = 0, old = 0,
           swap = 0, nonFinite = 0, resets = 0, silences = 0, silentTicks = 0, bursts = 0,
           burstTicks = 0, mirrored = 0, exact = 0, settled = 0, perturbed = 0, noLoad = 0;
  double maxSettled = 0.0, maxAfterFault = 0.0;
  uint64_t errors = 0;
  std::vector<std::string> firstErrors;
  void error(const std::string& what) {
    if (++errors <= 20) firstErrors.push_back(what);
  }
};

std::string seconds(int64_t ns) {
  return std::to_string(static_cast<double>(ns) * 1e-9);
}

/// The pid of a node, from its own XML-RPC getPid (never by process name: other rostests may run
/// contact_nodes on this machine at the same time). -1 if it cannot be found.
int nodePid(const std::string& node) {
  XmlRpc::XmlRpcValue req, res, payload;
  req[0] = ros::this_node::getName();
  req[1] = node;
  if (!ros::master::execute("lookupNode", req, res, payload, false)) return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue args, result;
  args[0] = ros::this_node::getName();
  if (!client.execute("getPid", args, result) ||
      result.getType() != XmlRpc::XmlRpcValue::TypeArray || result.size() < 3 ||
      static_cast<int>(result[0]) != 1)
    return -1;
  return static_cast<int>(result[2]);
}

/// VmRSS of a process [kB], -1 if unreadable.
long rssKb(int pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

uint64_t number(const std::string& text) {
  return text.empty() || text == "?" ? 0 : std::stoull(text);
}

double relDiff(const ContactState& s, const StepOutput& o, const ContactParameters& p) {
  const double F = p.mu * p.fz0;
  return std::max({std::fabs(s.fx - o.fx) / F, std::fabs(s.fy - o.fy) / F,
                   std::fabs(s.mz - o.mz) / (F * p.a0)});
}

/// One contact_node under stress: its inputs, its faults, the check of its outputs and two
/// in-process reference models.
class StressContact {
 public:
  StressContact(ros::NodeHandle& nh, const std::string& ns, const Options& o, std::mt19937_64& rng)
      : ns_(ns),
        o_(o),
        p_(parametersOf("/" + ns + "/contact_node")),
        scene_(rng, p_),
        mirror_(wheel_rail_contact::makeContactModel(p_)),
        clean_(wheel_rail_contact::makeContactModel(p_)) {
    const auto hints = ros::TransportHints().tcpNoDelay();
    creepPub_ = nh.advertise<wheel_rail_contact::Creepage>(ns + "/creepage", 1000);
    loadPub_ = nh.advertise<wheel_rail_contact::NormalLoad>(ns + "/normal_load", 1000);
    stateSub_ = nh.subscribe(ns + "/contact_state", 1000, &StressContact::onState, this, hints);
    forceSub_ = nh.subscribe(ns + "/creep_force", 1000, &StressContact::onForce, this, hints);
    resetProbe_ = nh.serviceClient<wheel_rail_contact::Reset>(ns + "/reset");
  }

  bool connected(ros::NodeHandle& nh) {
    // reset through a persistent client, made once the service exists (doc/vehicle_interface.md):
    // a fresh connection per call lost the node's answer now and then at 2 kHz on two cores (the
    // node had reset; the call returned false), as in ros/ros_comm#1976.
    if (!reset_ && resetProbe_.exists())
      reset_ = nh.serviceClient<wheel_rail_contact::Reset>(ns_ + "/reset", true);
    return creepPub_.getNumSubscribers() > 0 && loadPub_.getNumSubscribers() > 0 &&
           stateSub_.getNumPublishers() > 0 && forceSub_.getNumPublishers() > 0 && reset_;
  }

  void primeLoad() { publishLoad(0); }

  /// Every output of what was sent has arrived.
  bool caughtUp() const {
    return states_.size() >= pending_.size() && forces_.size() >= pending_.size();
  }

  /// Publishes tick k's load and creepage(s) as the fault plan says; a reset comes first.
  void sendTick(int64_t k, Tally* t) {
    if (plan.reset.count(k)) callReset(t);
    if (plan.silentAt(k)) {
      ++t->silentTicks;
    } else {
      publishLoad(k);
      ++t->loads;
    }
    if (plan.swap.count(k)) {  // k + 1 overtakes k: k is rejected, k + 1 steps over 2 ticks
      sendCreepage(canonical(k + 1), t);
      Sent late = canonical(k);
      late.overtaken = true;
      sendCreepage(late, t);
      ++t->swap;
    } else if (!plan.swap.count(k - 1)) {
      sendCreepage(canonical(k), t);
    }
    if (plan.duplicate.count(k)) {
      Sent d = canonical(k);
      d.kind = Kind::kDuplicate;
      sendCreepage(d, t);
      ++t->duplicate;
    }
    if (plan.old.count(k)) {
      const int64_t back = 1 + (k * 7919) % std::min<int64_t>(k, 100);  // 1..100 ticks back
      Sent d = canonical(k - back);
      d.kind = Kind::kOld;
      sendCreepage(d, t);
      ++t->old;
    }
    if (plan.nonFinite.count(k)) {
      Sent d = canonical(k);
      d.stampNs += o_.tickNs() / 2;  // would be in order: rejected for the NaN alone
      d.in.eta = std::numeric_limits<double>::quiet_NaN();
      d.kind = Kind::kNonFinite;
      sendCreepage(d, t);
      ++t->nonFinite;
    }
  }

  /// Checks every output received since the last call (all of them have arrived: caughtUp()).
  void check(Tally* t) {
    if (states_.size() != pending_.size() || forces_.size() != pending_.size())
      t->error(ns_ + ": " + std::to_string(pending_.size()) + " creepages sent, " +
               std::to_string(states_.size()) + " contact_state, " +
               std::to_string(forces_.size()) + " creep_force");
    std::vector<std::pair<Sent, ContactState>> canon;
    for (size_t i = 0; i < pending_.size() && i < states_.size() && i < forces_.size(); ++i) {
      checkOne(pending_[i], states_[i], forces_[i], t);
      if (pending_[i].kind == Kind::kCanonical) canon.emplace_back(pending_[i], states_[i]);
    }
    t->states += states_.size();
    t->forces += forces_.size();
    pending_.clear();
    states_.clear();
    forces_.clear();
    std::sort(canon.begin(), canon.end(),
              [](const auto& a, const auto& b) { return a.first.tick < b.first.tick; });
    for (const auto& c : canon) compareClean(c.first, c.second, t);
  }

  std::string node() const { return "/" + ns_ + "/contact_node"; }
  const std::string& ns() const { return ns_; }
  const ContactParameters& parameters() const { return p_; }
  int64_t firstPerturbed() const { return firstPerturbed_; }
  FaultPlan plan;

 private:
  Sent canonical(int64_t k) const {
    const double t = static_cast<double>(k) / o_.rate;
    return {kT0Ns + k * o_.tickNs(), k, scene_.at(t), Kind::kCanonical, false, {}};
  }

  void publishLoad(int64_t k) {
    wheel_rail_contact::NormalLoad m;
    m.header.stamp.fromNSec(kT0Ns + k * o_.tickNs());
    m.force = canonical(k).in.fz;
    loadPub_.publish(m);
    loads_[k] = m.force;
    if (loads_.size() > 4) loads_.erase(loads_.begin());
  }

  void sendCreepage(Sent s, Tally* t) {
    if (s.kind == Kind::kCanonical)
      for (int64_t j : {s.tick, s.tick - 1})
        if (loads_.count(j)) s.allowedFz.push_back(loads_.at(j));
    wheel_rail_contact::Creepage m;
    m.header.stamp.fromNSec(s.stampNs);
    m.velocity = s.in.V;
    m.longitudinal = s.in.xi;
    m.lateral = s.in.eta;
    m.spin = s.in.phi;
    creepPub_.publish(m);
    pending_.push_back(s);
    ++t->creepages;
  }

  void callReset(Tally* t) {
    wheel_rail_contact::Reset srv;
    if (!reset_.call(srv) || !srv.response.success) t->error(ns_ + ": reset call failed");
    mirror_->reset();
    hasStamp_ = false;
    hasAccepted_ = false;
    noLoadAllowed_ = true;
    loads_.clear();
    ++t->resets;
  }

  /// One output pair against what was sent and against the mirror model.
  void checkOne(const Sent& s, const ContactState& st, const geometry_msgs::WrenchStamped& w,
                Tally* t) {
    const std::string at = ns_ + " @" + seconds(s.stampNs) + ": ";
    if (static_cast<int64_t>(st.header.stamp.toNSec()) != s.stampNs ||
        static_cast<int64_t>(w.header.stamp.toNSec()) != s.stampNs)
      return t->error(at + "outputs out of step with the inputs (stamp " +
                      seconds(st.header.stamp.toNSec()) + ")");
    if (w.wrench.force.x != st.fx || w.wrench.force.y != st.fy || w.wrench.force.z != st.fz ||
        w.wrench.torque.z != st.mz)
      t->error(at + "creep_force differs from contact_state");
    for (double v : {st.fx, st.fy, st.fz, st.mz, st.a, st.b, st.adhesion_fraction, st.dt})
      if (!std::isfinite(v)) return t->error(at + "non-finite output");
    if (s.kind != Kind::kCanonical) {
      if (st.status != ContactState::STATUS_REJECTED)
        t->error(at + "a fault message was not rejected: " + st.message);
      checkHeld(st, at, t);
      const char* why = s.kind == Kind::kNonFinite ? "not finite" : "not after";
      if (st.message.find(why) == std::string::npos) t->error(at + "rejected for " + st.message);
      ++t->rejected;
      return;
    }
    if (s.overtaken || st.status == ContactState::STATUS_REJECTED) {
      if (!s.overtaken || st.status != ContactState::STATUS_REJECTED ||
          st.message.find("not after") == std::string::npos)
        t->error(at + "only the overtaken half of a swapped pair is rejected: " + st.message);
      checkHeld(st, at, t);
      ++t->rejected;
      return;
    }
    accepted_ = st;
    hasAccepted_ = true;
    checkDt(s, st, at, t);
    mirrorStep(s, st, at, t);
  }

  /// A rejected step publishes the last accepted step's output (zero forces before any).
  void checkHeld(const ContactState& st, const std::string& at, Tally* t) const {
    const bool same = hasAccepted_ ? st.held && st.fx == accepted_.fx && st.fy == accepted_.fy &&
                                         st.fz == accepted_.fz && st.mz == accepted_.mz
                                   : !st.held && st.fx == 0.0 && st.fy == 0.0 && st.mz == 0.0;
    if (!same) t->error(at + "a rejected step does not hold the last accepted output");
  }

  void checkDt(const Sent& s, const ContactState& st, const std::string& at, Tally* t) {
    const double dt = hasStamp_ ? static_cast<double>(s.stampNs - lastStampNs_) * 1e-9 : 0.0;
    if (st.dt != dt) t->error(at + "dt " + std::to_string(st.dt) + " != " + std::to_string(dt));
    hasStamp_ = true;
    lastStampNs_ = s.stampNs;
  }

  void mirrorStep(const Sent& s, const ContactState& st, const std::string& at, Tally* t) {
    if (st.status == ContactState::STATUS_NO_LOAD) {
      if (!noLoadAllowed_ || st.fz != 0.0) t->error(at + "no load: " + st.message);
      ++t->noLoad;
    } else if (st.status != ContactState::STATUS_OK) {
      t->error(at + "status " + std::to_string(st.status) + ": " + st.message);
    } else {
      noLoadAllowed_ = false;
    }
    const StepOutput m = mirror_->step({st.dt, s.in.V, s.in.xi, s.in.eta, s.in.phi, st.fz});
    if (m.fx != st.fx || m.fy != st.fy || m.mz != st.mz || m.a != st.a || m.b != st.b ||
        m.adhesionFraction != st.adhesion_fraction ||
        wheel_rail_contact::contactStateStatus(m.status) != st.status)
      t->error(at + "differs from the core model fed the same dt and fz (mirror)");
    ++t->mirrored;
  }

  /// The canonical output of tick s.tick against the fault-free run.
  void compareClean(const Sent& s, const ContactState& st, Tally* t) {
    const bool usedAllowed =
        std::find(s.allowedFz.begin(), s.allowedFz.end(), st.fz) != s.allowedFz.end();
    const double dtTick = static_cast<double>(o_.tickNs()) * 1e-9;
    const double dt = s.tick == 0 ? 0.0 : dtTick;
    const bool ok =
        st.status == ContactState::STATUS_OK && usedAllowed && st.dt == dt && s.tick == nextTick_;
    const double fz = ok ? st.fz : s.in.fz;  // the load the node was sent, as a clean run has it
    while (nextTick_ < s.tick) stepClean(canonical(nextTick_++).in, dtTick);  // a swapped tick
    const StepOutput c = stepClean({s.in.V, s.in.xi, s.in.eta, s.in.phi, fz}, dt);
    nextTick_ = s.tick + 1;
    rolled_ += s.in.V * dt;
    if (!ok) {
      if (firstPerturbed_ < 0) firstPerturbed_ = s.tick;
      lastPerturbed_ = s.tick;
      rolled_ = 0.0;
      ++t->perturbed;
      return;
    }
    const double d = relDiff(st, c, p_);
    if (firstPerturbed_ < 0) {
      if (d != 0.0) t->error(ns_ + ": differs from the clean run before any fault");
      ++t->exact;
    } else if (rolled_ > o_.settle * 2.0 * p_.a0) {
      t->maxSettled = std::max(t->maxSettled, d);
      if (d > o_.tolerance)
        t->error(ns_ + " @" + seconds(s.stampNs) + ": " + std::to_string(d) +
                 " of mu fz0 from the clean run, " +
                 std::to_string(static_cast<double>(s.tick - lastPerturbed_) / o_.rate) +
                 " s after the last fault (" + std::to_string(rolled_ / (2.0 * p_.a0)) +
                 " patch lengths)");
      ++t->settled;
    } else {
      t->maxAfterFault = std::max(t->maxAfterFault, d);
    }
  }

  StepOutput stepClean(const Inputs& in, double dt) {
    return clean_->step({dt, in.V, in.xi, in.eta, in.phi, in.fz});
  }

  void onState(const ContactState::ConstPtr& m) { states_.push_back(*m); }
  void onForce(const geometry_msgs::WrenchStamped::ConstPtr& m) { forces_.push_back(*m); }

  std::string ns_;
  Options o_;
  ContactParameters p_;
  Scene scene_;
  std::unique_ptr<wheel_rail_contact::ContactModel> mirror_, clean_;
  ros::Publisher creepPub_, loadPub_;
  ros::Subscriber stateSub_, forceSub_;
  ros::ServiceClient resetProbe_, reset_;  // the service's existence; the persistent caller
  std::deque<Sent> pending_;               // sent, outputs not yet checked
  std::vector<ContactState> states_;
  std::vector<geometry_msgs::WrenchStamped> forces_;
  std::map<int64_t, double> loads_;  // the last few loads published, by tick
  bool hasStamp_ = false, noLoadAllowed_ = true, hasAccepted_ = false;
  ContactState accepted_;  // the last output that was not rejected
  int64_t lastStampNs_ = 0, nextTick_ = 0, firstPerturbed_ = -1, lastPerturbed_ = -1;
  double rolled_ = 0.0;  // distance rolled since the last perturbed tick [m]
};

/// `n` ticks drawn uniformly from [from, to), none next to another or to one in `avoid`.
std::set<int64_t> pick(std::mt19937_64& rng, int n, int64_t from, int64_t to,
                       const std::set<int64_t>& avoid = {}) {
  std::uniform_int_distribution<int64_t> u(from, to - 1);
  std::set<int64_t> s;
  for (int tries = 0; static_cast<int>(s.size()) < n && tries < 100 * n; ++tries) {
    const int64_t k = u(rng);
    bool free = true;
    for (int64_t j : {k - 1, k, k + 1}) free = free && !avoid.count(j) && !s.count(j);
    if (free) s.insert(k);
  }
  return s;
}

/// A fault count for 60 s of sim time, scaled to the run's duration.
int count(const Options& o, int per60s) {
  return std::max(2, static_cast<int>(per60s * o.duration / 60.0 + 0.5));
}

/// The seeded fault plan of one contact. Faults fall in [1 s, duration - 1.5 s): the run starts
/// and ends clean. A reset in the middle of the run for every contact, one more at random; resets
/// and swaps keep clear of the load silences and of each other.
FaultPlan planFaults(std::mt19937_64& rng, const Options& o) {
  FaultPlan f;
  const int64_t from = static_cast<int64_t>(o.rate),
                to = o.ticks() - static_cast<int64_t>(1.5 * o.rate);
  std::uniform_int_distribution<int64_t> len(static_cast<int64_t>(0.1 * o.rate),
                                             static_cast<int64_t>(0.5 * o.rate));
  for (int64_t start : pick(rng, count(o, 4), from, to - static_cast<int64_t>(0.5 * o.rate)))
    f.silent.emplace_back(start, start + len(rng));
  std::set<int64_t> busy;
  for (const auto& s : f.silent)
    for (int64_t k = s.first - 2; k <= s.second + 2; ++k) busy.insert(k);
  if (!busy.count(o.ticks() / 2)) f.reset.insert(o.ticks() / 2);
  for (int64_t k : f.reset) busy.insert(k);
  for (int64_t k : pick(rng, 1, from, to, busy)) f.reset.insert(k);
  for (int64_t k : f.reset) busy.insert(k);
  f.swap = pick(rng, count(o, 20), from, to, busy);
  f.duplicate = pick(rng, count(o, 200), from, to);
  f.old = pick(rng, count(o, 200), from, to);
  f.nonFinite = pick(rng, count(o, 50), from, to);
  return f;
}

class Stress : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle pnh("~");
    pnh.param("duration", o.duration, o.duration);
    pnh.param("rate", o.rate, o.rate);
    pnh.param("seed", o.seed, o.seed);
    pnh.param("settle", o.settle, o.settle);
    pnh.param("tolerance", o.tolerance, o.tolerance);
    pnh.param("rss_tolerance_kb", o.rssToleranceKb, o.rssToleranceKb);
    std::mt19937_64 rng(static_cast<uint64_t>(o.seed));
    for (const char* ns : kContacts) {
      contacts.push_back(std::make_unique<StressContact>(nh, ns, o, rng));
      contacts.back()->plan = planFaults(rng, o);
    }
    clock = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    diagnostics = nh.subscribe("/diagnostics", 100, &Stress::onDiagnostics, this);
  }

  bool waitForOutputs(double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    auto done = [&] {
      for (const auto& c : contacts)
        if (!c->caughtUp()) return false;
      return true;
    };
    while (!done()) {
      if (!ros::ok() || ros::WallTime::now() > end) return false;
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.01));
    }
    return true;
  }

  void publishClock(int64_t k) {
    rosgraph_msgs::Clock m;
    m.clock.fromNSec(kT0Ns + k * o.tickNs());
    clock.publish(m);
  }

  void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
    for (const auto& st : m->status)
      for (const auto& c : contacts) {
        const std::string suffix = "contact /" + c->ns();
        if (st.name.size() >= suffix.size() &&
            st.name.compare(st.name.size() - suffix.size(), suffix.size(), suffix) == 0)
          for (const auto& kv : st.values) diag[c->ns()][kv.key] = kv.value;
      }
  }

  /// The latest diagnostics value `key` of a contact, "?" if none yet.
  std::string counted(const StressContact& c, const std::string& key) const {
    auto d = diag.find(c.ns());
    if (d == diag.end() || !d->second.count(key)) return "?";
    return d->second.at(key);
  }

  std::vector<long> sampleRss() {
    std::vector<long> r;
    for (int pid : pids) r.push_back(rssKb(pid));
    return r;
  }

  Options o;
  ros::NodeHandle nh;
  std::vector<std::unique_ptr<StressContact>> contacts;
  ros::Publisher clock;
  ros::Subscriber diagnostics;
  std::map<std::string, std::map<std::string, std::string>> diag;
  std::vector<int> pids;
};

}  // namespace

TEST_F(Stress, EightContactsUnderFaultsAtTwoKilohertz) {
  ASSERT_TRUE(spinUntil(
      [&] {
        for (const auto& c : contacts)
          if (!c->connected(nh)) return false;
        return clock.getNumSubscribers() >= static_cast<uint32_t>(contacts.size());
      },
      30.0))
      << "contact_nodes not up";
  std::set<std::string> meshes;
  for (const auto& c : contacts) {
    EXPECT_EQ(c->parameters().model, "nss") << c->ns();
    meshes.insert(c->parameters().mesh);
    pids.push_back(nodePid(c->node()));
    ASSERT_GT(pids.back(), 0) << c->node();
    std::ifstream cmd("/proc/" + std::to_string(pids.back()) + "/cmdline");
    std::string text((std::istreambuf_iterator<char>(cmd)), std::istreambuf_iterator<char>());
    ASSERT_NE(text.find("contact_node"), std::string::npos) << pids.back();
  }
  EXPECT_EQ(meshes, (std::set<std::string>{"adaptive", "fixed"}));
  // Tick 0's load must be in before tick 0's creepage (else it says no load and the run starts
  // perturbed): the diagnostics confirm it arrived.
  for (auto& c : contacts) c->primeLoad();
  ASSERT_TRUE(spinUntil(
      [&] {
        for (const auto& c : contacts)
          if (number(counted(*c, "normal_load messages")) == 0) return false;
        return true;
      },
      10.0))
      << "no diagnostics counting the first load";

  // Bursts: every contact's inputs of 20-50 ticks at once, then all their outputs.
  std::mt19937_64 rng(static_cast<uint64_t>(o.seed) + 1);
  std::set<int64_t> resets;
  for (const auto& c : contacts) resets.insert(c->plan.reset.begin(), c->plan.reset.end());
  std::map<int64_t, int64_t> bursts;  // first tick -> ticks
  std::uniform_int_distribution<int64_t> burstLen(20, 50);
  for (int64_t k : pick(rng, count(o, 40), static_cast<int64_t>(o.rate),
                        o.ticks() - static_cast<int64_t>(2 * o.rate)))
    bursts[k] = burstLen(rng);

  Tally t;
  const int64_t n = o.ticks();
  std::vector<long> early, late, peak(contacts.size(), 0);
  const ros::WallTime start = ros::WallTime::now();
  int64_t k = 0;
  while (k < n) {
    int64_t group = 1;
    auto b = bursts.find(k);
    if (b != bursts.end()) {
      group = std::min(b->second, n - k);
      for (int64_t j = k + 1; j < k + group; ++j)
        if (resets.count(j)) group = j - k;  // a reset waits for every output before it
      ++t.bursts;
      t.burstTicks += group;
    }
    for (int64_t j = k; j < k + group; ++j) {
      publishClock(j);  // sim time advances only once the previous outputs are all in
      for (auto& c : contacts) c->sendTick(j, &t);
    }
    k += group;
    if (!waitForOutputs(30.0)) {
      ADD_FAILURE() << "outputs missing 30 s (wall) after tick " << k;
      break;
    }
    for (auto& c : contacts) c->check(&t);
    if (k % std::max<int64_t>(1, n / 20) < group) {  // every 5 % of the run
      const std::vector<long> r = sampleRss();
      for (size_t i = 0; i < r.size(); ++i) peak[i] = std::max(peak[i], r[i]);
      if (early.empty() && k >= n / 10) early = r;
      std::printf("stress: %3.0f %% sim %.1f s wall %.1f s rss[0] %ld kB\n", 100.0 * k / n,
                  static_cast<double>(k) / o.rate, (ros::WallTime::now() - start).toSec(), r[0]);
      std::fflush(stdout);
    }
  }
  const double wall = (ros::WallTime::now() - start).toSec();
  late = sampleRss();
  for (const auto& c : contacts) t.silences += c->plan.silent.size();

  std::printf(
      "stress: %zu contacts, %.1f s sim at %.0f Hz in %.1f s wall (%.2fx real time)\n"
      "  creepage %lu, normal_load %lu, contact_state %lu, creep_force %lu\n"
      "  faults: bursts %lu (%lu ticks), duplicates %lu, old stamps %lu, swapped pairs %lu, "
      "non-finite %lu, load silences %lu (%lu ticks), resets %lu; rejected %lu, no load %lu\n"
      "  mirror steps %lu (bit-identical); clean: %lu ticks exact before the first fault, %lu "
      "compared after settling (max %.3g of mu fz0), %lu perturbed (max %.3g right after)\n",
      contacts.size(), k / o.rate, o.rate, wall, k / o.rate / wall, t.creepages, t.loads, t.states,
      t.forces, t.bursts, t.burstTicks, t.duplicate, t.old, t.swap, t.nonFinite, t.silences,
      t.silentTicks, t.resets, t.rejected, t.noLoad, t.mirrored, t.exact, t.settled, t.maxSettled,
      t.perturbed, t.maxAfterFault);
  for (size_t i = 0; i < contacts.size(); ++i)
    std::printf("  %s pid %d VmRSS early %ld kB, late %ld kB, peak %ld kB\n",
                contacts[i]->ns().c_str(), pids[i], early.empty() ? -1 : early[i], late[i],
                peak[i]);
  std::fflush(stdout);

  for (const auto& e : t.firstErrors) ADD_FAILURE() << e;
  EXPECT_EQ(t.errors, 0u);
  EXPECT_EQ(t.states, t.creepages);
  EXPECT_EQ(t.forces, t.creepages);
  EXPECT_EQ(t.rejected, t.duplicate + t.old + t.swap + t.nonFinite);
  EXPECT_GT(t.exact, 0u);
  EXPECT_GT(t.settled, static_cast<uint64_t>(n) * contacts.size() / 2)
      << "too few ticks compared after the faults";
  EXPECT_GT(t.maxAfterFault, 100 * o.tolerance) << "the faults left no trace: a vacuous check";
  ASSERT_EQ(early.size(), contacts.size());
  for (size_t i = 0; i < contacts.size(); ++i)
    EXPECT_LE(late[i] - early[i], o.rssToleranceKb) << contacts[i]->ns() << " grows";

  // The nodes' own counts (diagnostics run on wall time; wait for the final counts).
  EXPECT_TRUE(spinUntil(
      [&] {
        uint64_t total = 0;
        for (const auto& c : contacts) {
          total += number(counted(*c, "creepage messages"));
        }
        return total == t.creepages;
      },
      10.0))
      << "diagnostics never counted every creepage";
  uint64_t outOfOrder = 0, nonFinite = 0, resetsCounted = 0;
  for (const auto& c : contacts) {
    EXPECT_EQ(counted(*c, "creepage lost before the node (queue_size)"), "0") << c->ns();
    EXPECT_NE(counted(*c, "stale load steps"), "0") << c->ns() << ": load silences not seen";
    outOfOrder += number(counted(*c, "rejected: creepage stamp out of order"));
    nonFinite += number(counted(*c, "rejected: non-finite"));
    resetsCounted += number(counted(*c, "resets"));
  }
  EXPECT_EQ(outOfOrder, t.duplicate + t.old + t.swap);
  EXPECT_EQ(nonFinite, t.nonFinite);
  EXPECT_EQ(resetsCounted, t.resets);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "stress");
  return RUN_ALL_TESTS();
}
