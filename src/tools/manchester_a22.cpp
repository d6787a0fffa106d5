// The Manchester contact benchmark's case through our chain, for every case and both wheels:
// contact search, the normal problem under the wheel load, creepages, and the exact half-space
// solver on each patch's gap (validation/manchester_a22.hpp). Writes one row per case, wheel and
// patch (ours, exact, and CONTACT's published reference point beside them) to --out, and the
// pressure maps at --map-y (our strips and the exact grid) next to it. doc/manchester.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "validation/manchester_a22.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string cases = "test/data/profiles/a22_cases.csv";
  std::string reference = "test/data/profiles/contact_a22_reference.csv";
  std::string out = "doc/data/manchester_a22.csv";
  std::string maps = "doc/data/manchester_a22";  ///< prefix of the pressure maps' files
  std::vector<double> map_y = {0.0, 0.5, 5.0, 6.5};
  std::string map_wheel = "right";
  int exact_mx = 48, exact_my = 32;
  double G = 82e9, nu = 0.28;
  bool contact_table = false;
  bool continuous_region = NormalOptions{}.continuous_region;
  std::string creep_out = "doc/data/manchester_a22_creep.csv";
  std::vector<std::string> creep_models = {"steady", "nss", "shen-li"};
  int creep_mx = 32, creep_my = 24;
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Manchester benchmark case A-2.2: our contact search, normal problem and creepages against "
      "the exact half-space solver, CONTACT's published results beside them.");
  tools::option(app, "--cases", &o->cases, "the benchmark's wheelset states (a22_cases.csv)");
  tools::option(app, "--reference", &o->reference, "CONTACT's results (contact_a22_reference.csv)");
  tools::option(app, "--out", &o->out, "the table, one row per case, wheel and patch");
  tools::option(
      app, "--maps", &o->maps,
      "prefix of the pressure maps (<prefix>_strips.csv, <prefix>_exact_map.csv); '' none");
  tools::option(app, "--map-y", &o->map_y, "lateral displacements of the pressure maps [mm]");
  tools::option(app, "--map-wheel", &o->map_wheel, "the wheel of the pressure maps")
      ->check(CLI::IsMember({"left", "right"}));
  tools::option(app, "--exact-mx", &o->exact_mx, "exact grid: elements along x per patch");
  tools::option(app, "--exact-my", &o->exact_my, "exact grid: elements across per patch");
  app.add_flag_callback(
      "--no-continuous-region", [o] { o->continuous_region = false; },
      "the normal problem with NormalOptions::continuous_region = false (its rule before "
      "continuous_region became the default)");
  app.add_flag("--contact-table", o->contact_table,
               "take the geometry from the contact table (ContactTable, default options) instead "
               "of the direct search, and print the largest differences between the two in our "
               "normal force, peak pressure and contact point");
  tools::option(app, "--creep-out", &o->creep_out,
                "the creep forces, one row per case, wheel and loaded patch: each model through "
                "WheelsetContact (nss, shen-li at the constant state until settled) against the "
                "exact tangential solution on the same patch; '' none");
  tools::option(app, "--creep-models", &o->creep_models, "the models of --creep-out");
  tools::option(app, "--creep-mx", &o->creep_mx,
                "exact grid of the creep forces: elements along x per patch");
  tools::option(app, "--creep-my", &o->creep_my,
                "exact grid of the creep forces: elements across per patch");
  tools::option(app, "--G", &o->G, "shear modulus [Pa]");
  tools::option(app, "--nu", &o->nu, "Poisson's ratio");
}

const char* sideName(WheelSide s) {
  return s == WheelSide::kLeft ? "left" : "right";
}
const char* zoneName(ContactZone z) {
  return z == ContactZone::kTread ? "tread" : z == ContactZone::kFlange ? "flange" : "corner";
}
const char* methodName(NormalMethod m) {
  return m == NormalMethod::kHertz ? "hertz" : "non-hertzian";
}
/// Our method on patch p: "lumps" for a patch other candidates merged into, "merged" for one
/// merged into another.
std::string methodOf(const A22Patch& p) {
  if (p.ours.merged_into >= 0) return "merged";
  if (p.merged_last > p.merged_first) return "lumps";
  return methodName(p.ours.method);
}
/// The row's status: ok, or which patch took this candidate over.
std::string statusOf(const A22Patch& p) {
  if (p.ours.merged_into >= 0) return "merged into patch " + std::to_string(p.ours.merged_into);
  if (p.merged_last > p.merged_first)
    return "ok: candidates " + std::to_string(p.merged_first) + " to " +
           std::to_string(p.merged_last) + " merged";
  return "ok";
}

/// v printed with fmt, or "-" when NaN (no reference point).
std::string shown(double v, const char* fmt) {
  if (std::isnan(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

bool onMap(const Options& o, double y_mm) {
  for (double y : o.map_y)
    if (std::abs(y - y_mm) < 1e-9) return true;
  return false;
}

/// The creep forces of every loaded patch against the exact tangential solution (--creep-out), and
/// each model's largest error in % of mu fn over the cases.
void runCreep(const Options& o, const ContactSearch& search, const std::vector<A22State>& states,
              const std::vector<A22Reference>& refs) {
  A22Options ao;
  ao.G = o.G;
  ao.nu = o.nu;
  ao.exact_mx = o.creep_mx;
  ao.exact_my = o.creep_my;
  ao.normal.continuous_region = o.continuous_region;
  A22CreepOptions co;
  co.models = o.creep_models;
  std::ofstream out = tools::writeFile(o.creep_out);
  out << "wheel,case,y_mm,patch,zone,fn_N,a_mm,b_mm,xi,eta,phi_per_m,exact_fx_N,exact_fs_N,"
         "exact_mz_Nm,exact_adhesion,exact_converged,exact_on_ours_fx_N,exact_on_ours_fs_N,"
         "exact_on_ours_mz_Nm";
  for (std::string m : co.models) {
    std::replace(m.begin(), m.end(), '-', '_');
    for (const char* c : {"_fx_N", "_fs_N", "_mz_Nm", "_err_fx_pct", "_err_fs_pct", "_err_mz_pct",
                          "_status", "_steps"})
      out << "," << m << c;
  }
  out << ",contact_fn_N,contact_fx_N,contact_fs_N,contact_mz_Nm\n";
  // Per model: the largest |error| in % of mu fn on fx and fs, and where.
  std::vector<double> worst(co.models.size(), 0.0);
  std::vector<std::string> where(co.models.size());
  for (const A22State& s : states) {
    const A22Wheel w = runA22Wheel(search, s, ao);
    for (const A22Creep& k : runA22Creep(w, ao, co, refs)) {
      char line[512];
      std::snprintf(line, sizeof line,
                    "%s,%d,%g,%d,%s,%.1f,%.4f,%.4f,%.4e,%.4e,%.4e,%.2f,%.2f,%.4f,%.3f,%d",
                    sideName(s.side), s.number, s.y_mm, k.index, zoneName(k.zone), k.fn, k.a * 1e3,
                    k.b * 1e3, k.creepages.xi, k.creepages.eta, k.creepages.phi, k.exact.fx,
                    k.exact.fs, k.exact.mz, k.exact.adhesion_fraction, k.exact.converged ? 1 : 0);
      out << line;
      std::snprintf(line, sizeof line, ",%.2f,%.2f,%.4f", k.exact_on_ours.fx, k.exact_on_ours.fs,
                    k.exact_on_ours.mz);
      out << line;
      const double scale = co.mu * k.fn, lever = std::sqrt(k.a * k.b);
      for (size_t i = 0; i < k.models.size(); ++i) {
        const A22ModelForces& f = k.models[i];
        const double ex = 100.0 * (f.fx - k.exact.fx) / scale,
                     es = 100.0 * (f.fs - k.exact.fs) / scale,
                     em = 100.0 * (f.mz - k.exact.mz) / (scale * lever);
        std::snprintf(line, sizeof line, ",%.2f,%.2f,%.4f,%.2f,%.2f,%.2f,%s,%d", f.fx, f.fs, f.mz,
                      ex, es, em, f.found ? toString(f.status) : "absent", f.steps);
        out << line;
        const double e = std::max(std::abs(ex), std::abs(es));
        if (e > worst[i]) {
          worst[i] = e;
          where[i] = std::string(sideName(s.side)) + " wheel, y " + shown(s.y_mm, "%.1f") +
                     " mm, " + zoneName(k.zone);
        }
      }
      if (k.contact)
        std::snprintf(line, sizeof line, ",%.0f,%.1f,%.1f,%.4f\n", k.contact->fn, k.contact->fx,
                      k.contact->fs, k.contact->mz);
      else
        std::snprintf(line, sizeof line, ",,,,\n");
      out << line;
    }
  }
  for (size_t i = 0; i < co.models.size(); ++i)
    std::printf("creep forces, %s: largest |error| on fx, fs %.2f %% of mu fn (%s)\n",
                co.models[i].c_str(), worst[i], where[i].c_str());
}

int run(const Options& o) {
  const std::vector<A22State> states = readA22States(o.cases);
  const std::vector<A22Reference> refs = readA22Reference(o.reference);
  A22Options ao;
  ao.G = o.G;
  ao.nu = o.nu;
  ao.exact_mx = o.exact_mx;
  ao.exact_my = o.exact_my;
  ao.normal.continuous_region = o.continuous_region;
  const ContactSearch search{WheelsetTrackData{}};
  std::unique_ptr<ContactTable> table;
  if (o.contact_table) table = std::make_unique<ContactTable>(search);
  // The contact table's results against the direct search's: the largest differences over the
  // wheels in our loaded patches' normal force, peak pressure and contact point on the rail.
  double most_fn = 0.0, most_pmax = 0.0, most_point = 0.0;
  std::string where_fn, where_pmax, where_point;
  int unmatched = 0;
  std::ofstream out = tools::writeFile(o.out);
  std::ofstream strips, exactMap;
  if (!o.maps.empty()) {
    strips = tools::writeFile(o.maps + "_strips.csv");
    exactMap = tools::writeFile(o.maps + "_exact_map.csv");
    strips << "wheel,y_mm,patch,method,eta_mm,width_mm,x_lead_mm,x_trail_mm,pmax_MPa,force_N\n";
    exactMap << "wheel,y_mm,patch,x_mm,eta_mm,dx_mm,deta_mm,p_MPa\n";
  }
  out << "wheel,case,y_mm,patch,zone,y_rail_mm,z_rail_mm,y_rail_centre_mm,contact_angle,"
         "rolling_radius_mm,xi,eta,phi_per_m,method,approach_um,fn_N,pmax_MPa,a_mm,b_mm,"
         "eta_min_mm,eta_max_mm,exact_fn_N,exact_pmax_MPa,exact_approach_um,"
         "exact_fn_at_our_approach_N,exact_eta_min_mm,exact_eta_max_mm,exact_x_min_mm,"
         "exact_x_max_mm,contact_y_rail_mm,contact_z_rail_mm,contact_angle_ref,contact_fn_N,"
         "contact_pmax_MPa,contact_approach_um,contact_cksi,contact_ceta,contact_cphi_per_m,"
         "status\n";
  std::printf("%-5s %4s %5s %6s %6s %8s %8s %8s %8s %8s %8s %8s %8s\n", "wheel", "y", "patch",
              "zone", "method", "y_rail", "CONTACT", "fn", "exact", "CONTACT", "pmax", "exact",
              "CONTACT");
  for (const A22State& s : states) {
    const A22Wheel w = table ? runA22Wheel(*table, s, ao) : runA22Wheel(search, s, ao);
    const std::string here =
        std::string(sideName(s.side)) + " wheel, y " + shown(s.y_mm, "%.1f") + " mm";
    if (table) {
      const A22Wheel d = runA22Wheel(search, s, ao);
      int loaded_w = 0, loaded_d = 0;
      for (const A22Patch& p : w.patches) loaded_w += p.ours.fn > 0.0;
      for (const A22Patch& p : d.patches) loaded_d += p.ours.fn > 0.0;
      if (!w.message.empty() || !d.message.empty() || loaded_w != loaded_d) ++unmatched;
      for (const A22Patch& p : w.patches) {
        if (p.ours.fn <= 0.0) continue;
        // the direct search's loaded patch nearest on the rail
        const double y = railFilePointAt(p.candidate, p.ours.eta_centre).x();
        const A22Patch* q = nullptr;
        double dist = std::numeric_limits<double>::infinity();
        for (const A22Patch& r : d.patches) {
          if (r.ours.fn <= 0.0) continue;
          const double e = std::abs(railFilePointAt(r.candidate, r.ours.eta_centre).x() - y);
          if (e < dist) dist = e, q = &r;
        }
        if (!q) continue;
        const double dfn = std::abs(p.ours.fn / q->ours.fn - 1.0);
        const double dp = std::abs(p.ours.pmax / q->ours.pmax - 1.0);
        if (dfn > most_fn) most_fn = dfn, where_fn = here;
        if (dp > most_pmax) most_pmax = dp, where_pmax = here;
        if (dist > most_point) most_point = dist, where_point = here;
      }
    }
    if (!w.message.empty()) {
      std::printf("%-5s %4.1f failed: %s\n", sideName(s.side), s.y_mm, w.message.c_str());
      std::string why = w.message;
      std::replace(why.begin(), why.end(), ',', ';');
      out << sideName(s.side) << "," << s.number << "," << s.y_mm << std::string(35, ',') << why
          << "\n";
      continue;
    }
    // CONTACT's patches of this wheel and case, each beside our loaded patch nearest on the rail.
    std::map<int, const A22Reference*> beside;
    for (const A22Reference& r : refs) {
      if (r.side != s.side || r.number != s.number) continue;
      int best = -1;
      double dist = std::numeric_limits<double>::infinity();
      for (const A22Patch& p : w.patches) {
        if (p.ours.fn <= 0.0 && p.exact.fn <= 0.0) continue;
        const double d = std::abs(railFilePointAt(p.candidate, p.ours.eta_centre).x() - r.y_rail);
        if (d < dist) dist = d, best = p.index;
      }
      if (best >= 0) beside[best] = &r;
    }
    for (const A22Patch& p : w.patches) {
      if (p.ours.fn <= 0.0 && p.exact.fn <= 0.0 && p.ours.merged_into < 0) continue;
      const ContactCandidate& c = p.candidate;
      const Eigen::Vector2d centre = railFilePointAt(c, p.ours.eta_centre);
      char line[1024];
      std::snprintf(line, sizeof line,
                    "%s,%d,%g,%d,%s,%.4f,%.4f,%.4f,%.5f,%.3f,%.4e,%.4e,%.4e,%s,%.3f,%.1f,%.2f,"
                    "%.4f,%.4f,%.4f,%.4f,%.1f,%.2f,%.3f,%.1f,%.4f,%.4f,%.4f,%.4f",
                    sideName(s.side), s.number, s.y_mm, p.index, zoneName(c.zone),
                    c.rail_file.x() * 1e3, c.rail_file.y() * 1e3, centre.x() * 1e3, c.contact_angle,
                    c.rolling_radius * 1e3, p.creepages.xi, p.creepages.eta, p.creepages.phi,
                    methodOf(p).c_str(), p.ours.approach * 1e6, p.ours.fn, p.ours.pmax * 1e-6,
                    p.ours.a * 1e3, p.ours.b * 1e3, p.ours.eta_min * 1e3, p.ours.eta_max * 1e3,
                    p.exact.fn, p.exact.pmax * 1e-6, p.exact.approach * 1e6,
                    p.exact_fn_at_our_approach, p.exact.eta_min * 1e3, p.exact.eta_max * 1e3,
                    p.exact.x_min * 1e3, p.exact.x_max * 1e3);
      out << line;
      const auto r = beside.find(p.index);
      if (r != beside.end()) {
        const A22Reference& ref = *r->second;
        std::snprintf(line, sizeof line, ",%.4f,%.4f,%.4f,%.0f,%.1f,%.2f,%.4e,%.4e,%.4e,",
                      ref.y_rail * 1e3, ref.z_rail * 1e3, ref.contact_angle, ref.fn,
                      ref.pmax * 1e-6, ref.approach * 1e6, ref.cksi, ref.ceta, ref.cphi);
        out << line << statusOf(p) << "\n";
      } else {
        out << ",,,,,,,,,," << statusOf(p) << "\n";
      }
      const A22Reference* ref = r != beside.end() ? r->second : nullptr;
      if (p.ours.merged_into >= 0) {
        std::printf("%-5s %4.1f %5d %6s merged into patch %d\n", sideName(s.side), s.y_mm, p.index,
                    zoneName(c.zone), p.ours.merged_into);
        continue;
      }
      std::printf("%-5s %4.1f %5d %6s %6s %8.2f %8s %8.0f %8.0f %8s %8.0f %8.0f %8s\n",
                  sideName(s.side), s.y_mm, p.index, zoneName(c.zone),
                  p.merged_last > p.merged_first          ? "lumps"
                  : p.ours.method == NormalMethod::kHertz ? "hertz"
                                                          : "strips",
                  centre.x() * 1e3, shown(ref ? ref->y_rail * 1e3 : NAN, "%.2f").c_str(), p.ours.fn,
                  p.exact.fn, shown(ref ? ref->fn : NAN, "%.0f").c_str(), p.ours.pmax * 1e-6,
                  p.exact.pmax * 1e-6, shown(ref ? ref->pmax * 1e-6 : NAN, "%.0f").c_str());
      if (o.maps.empty() || !onMap(o, s.y_mm) || o.map_wheel != sideName(s.side)) continue;
      for (const NormalStrip& st : p.ours.strips)
        strips << sideName(s.side) << "," << s.y_mm << "," << p.index << "," << methodOf(p) << ","
               << st.eta * 1e3 << "," << st.width * 1e3 << "," << st.x_lead * 1e3 << ","
               << st.x_trail * 1e3 << "," << st.pmax * 1e-6 << "," << st.force << "\n";
      const HalfspaceGrid& g = p.exact.grid;
      for (int ix = 0; ix < g.mx; ++ix)
        for (int iy = 0; iy < g.my; ++iy) {
          const double pe = p.exact.p.size() ? p.exact.p[g.index(ix, iy)] : 0.0;
          if (pe <= 0.0) continue;
          exactMap << sideName(s.side) << "," << s.y_mm << "," << p.index << "," << g.xc(ix) * 1e3
                   << "," << (p.exact.eta_offset + g.yc(iy)) * 1e3 << "," << g.dx * 1e3 << ","
                   << g.dy * 1e3 << "," << pe * 1e-6 << "\n";
        }
    }
    if (!w.exact_converged)
      std::fprintf(stderr, "%s wheel, case %d: the exact wheel load did not converge\n",
                   sideName(s.side), s.number);
  }
  if (!o.creep_out.empty()) runCreep(o, search, states, refs);
  if (table)
    std::printf(
        "\ncontact table against the direct search, our loaded patches: fn at most %.3f %% "
        "(%s), pmax %.3f %% (%s), contact point on the rail %.4f mm (%s); wheels whose loaded "
        "patches differ in number or that fail on either: %d\n",
        100.0 * most_fn, where_fn.c_str(), 100.0 * most_pmax, where_pmax.c_str(), most_point * 1e3,
        where_point.c_str(), unmatched);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("manchester_a22", argc, argv, addOptions, run);
}
