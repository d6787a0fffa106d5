// The ticks wheelset_latency sends (4 wheelsets swaying on their treads: 3 mm and 1 mrad at 1.5
// Hz, 30 m/s, 60 +- 2 kN per wheel, 1 ms apart) through WheelsetContact on one shared contact
// table of default options, as wheelset_node steps them: how many wheel-steps the table's
// geometry leaves to the direct search (WheelsetContact::directSearchFallbacks, about 1 ms each)
// and how many are not ok. doc/wheelset_interface.md.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  int ticks = 10000;
  int wheelsets = 4;
  std::string model = "nss";
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "wheelset_latency's ticks through WheelsetContact on a contact table: the wheel-steps that "
      "search directly because the normal problem fails on the table's geometry");
  tools::option(app, "--ticks", &o->ticks, "ticks of 1 ms");
  tools::option(app, "--wheelsets", &o->wheelsets, "wheelsets per tick (each a phase of 1 rad on)");
  tools::option(app, "--model", &o->model, "the tangential model (ContactParameters::model)");
}

int run(const Options& o) {
  if (o.ticks < 1 || o.wheelsets < 1 || o.wheelsets > 16)
    throw std::invalid_argument("--ticks must be >= 1 and --wheelsets in [1, 16]");
  const WheelsetTrackData track;
  ContactParameters p;
  p.model = o.model;
  WheelsetContactOptions wo;
  wo.contact_table = std::make_shared<const ContactTable>(ContactSearch(track));
  std::vector<std::unique_ptr<WheelsetContact>> ws;
  for (int i = 0; i < o.wheelsets; ++i)
    ws.push_back(std::make_unique<WheelsetContact>(track, p, wo));
  long not_ok = 0;
  const double w_tick = 2.0 * M_PI * 1.5 * 1e-3;
  for (int k = 0; k < o.ticks; ++k)
    for (int i = 0; i < o.wheelsets; ++i) {
      // wheelset_latency's tick(): wheelset i a phase of i rad on.
      const double w = w_tick * k + i;
      WheelsetState s;
      s.pose.y = 3e-3 * std::sin(w);
      s.pose.yaw = 1e-3 * std::cos(w);
      s.motion.V = 30.0;
      s.motion.omega = 30.0 / 0.46;
      s.motion.vy = 3e-3 * 2.0 * M_PI * 1.5 * std::cos(w);
      s.motion.yaw_rate = -1e-3 * 2.0 * M_PI * 1.5 * std::sin(w);
      s.fz_left = 6e4 + 2e3 * std::sin(w);
      s.fz_right = 6e4 - 2e3 * std::sin(w);
      const WheelsetResult r = ws[i]->step(s, k > 0 ? 1e-3 : 0.0);
      not_ok += (r.left.status != WheelStatus::kOk) + (r.right.status != WheelStatus::kOk);
    }
  std::size_t direct = 0;
  for (const auto& w : ws) direct += w->directSearchFallbacks();
  std::printf("%ld wheel-steps: %zu searched directly, %ld not ok\n", 2L * o.ticks * o.wheelsets,
              direct, not_ok);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("table_fallbacks", argc, argv, addOptions, run);
}
