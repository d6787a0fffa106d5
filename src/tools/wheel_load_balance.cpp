// The wheel load balance with and without the tangential forces' vertical components
// (WheelsetContactOptions::whole_force_balance) on the Manchester benchmark's case, both
// wheels: per patch our normal force with the normal forces' balance (one step), with the whole
// forces' (a steady evaluation, WheelsetContact::settle), its tangential forces, and CONTACT's
// published normal force of the nearest patch beside them as a reference point. doc/wheelset.md.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "validation/manchester_a22.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string cases = "test/data/profiles/a22_cases.csv";
  std::string reference = "test/data/profiles/contact_a22_reference.csv";
  std::string model = "steady";
  double dt = 1.0;  ///< each repeat's step [s]: at the benchmark's 2 m/s, 2 m of rolling
  double tolerance = 1e-6;
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Manchester benchmark case A-2.2 through WheelsetContact: each patch's normal force with "
      "the normal forces' load balance and with the whole forces' (whole_force_balance, settled), "
      "CONTACT's published normal force beside them. One row per case, wheel and patch on stdout.");
  tools::option(app, "--cases", &o->cases, "the benchmark's wheelset states (a22_cases.csv)");
  tools::option(app, "--reference", &o->reference, "CONTACT's results (contact_a22_reference.csv)");
  tools::option(app, "--model", &o->model, "the tangential model (ContactParameters::model)");
  tools::option(app, "--dt", &o->dt, "each step's dt [s] (settle repeats the step)");
  tools::option(app, "--tolerance", &o->tolerance, "settle's tolerance on fn / load");
}

int run(const Options& o) {
  const std::vector<A22State> states = readA22States(o.cases);
  const std::vector<A22Reference> refs = readA22Reference(o.reference);
  ContactParameters p;
  p.model = o.model;
  WheelsetContactOptions whole;
  whole.whole_force_balance = true;
  std::printf(
      "side,y_mm,patch,contact_angle_rad,fn_normal_balance_N,fn_whole_balance_N,fx_N,fs_N,"
      "wheel_fz_N,contact_fn_N,message\n");
  for (const A22State& s : states) {
    WheelsetState st;
    st.pose = a22Pose(s);
    st.motion = a22Motion(s);
    st.fz_left = st.fz_right = s.fz;
    WheelsetContact plain(WheelsetTrackData{}, p);
    WheelsetContact balanced(WheelsetTrackData{}, p, whole);
    const WheelsetResult a = plain.step(st, o.dt);
    const WheelsetResult b = balanced.settle(st, o.dt, o.tolerance);
    const bool left = s.side == WheelSide::kLeft;
    const WheelResult& wa = left ? a.left : a.right;
    const WheelResult& wb = left ? b.left : b.right;
    if (wa.patches.size() != wb.patches.size()) {
      std::printf("%s,%.1f,patches differ,,,,,,,,%s\n", left ? "left" : "right", s.y_mm,
                  wb.message.c_str());
      continue;
    }
    for (size_t i = 0; i < wb.patches.size(); ++i) {
      const PatchResult& q = wb.patches[i];
      double contact = std::numeric_limits<double>::quiet_NaN(), best = 1e9;
      for (const A22Reference& r : refs)
        if (r.side == s.side && r.number == s.number &&
            std::abs(r.y_rail - q.geometry.rail_file.x()) < best) {
          best = std::abs(r.y_rail - q.geometry.rail_file.x());
          contact = r.fn;
        }
      std::printf("%s,%.1f,%s,%.4f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%s\n", left ? "left" : "right",
                  s.y_mm, q.slot.c_str(), q.geometry.contact_angle, wa.patches[i].normal.fn,
                  q.normal.fn, q.fx, q.fs, wb.wrench.fz, contact, wb.message.c_str());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("wheel_load_balance", argc, argv, addOptions, run);
}
