// The normal problem per patch (normal/patch_normal.hpp) against the exact half-space solver on
// the Manchester benchmark's case, right wheel, each state at the given wheel load: per
// loaded patch the method's normal force, peak pressure and lateral extent against the exact
// solution at the same approach, and where two patches share the load, each patch's share
// against the exact split of the same load; a patch merged across a ridge against the exact
// solution on the merged gap. Prints a markdown table (doc/normal_problem.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/normal/merge_candidates.hpp"
#include "tool_options.hpp"
#include "validation/manchester_a22.hpp"
#include "validation/patch_exact.hpp"
#include "wheel_rail_contact/normal/patch_normal.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string cases = "test/data/profiles/a22_cases.csv";
  double load = 1e4;  ///< vertical wheel load [N]
  double G = 8.2e10, nu = 0.28;
  int grid = 40;                                         ///< exact grid nx = ny
  double min_ridge = ContactSearchOptions{}.min_ridge;   ///< the contact search's [m]
  int gap_samples = ContactSearchOptions{}.gap_samples;  ///< the contact search's
  bool continuous_region = NormalOptions{}.continuous_region;
};

void addOptions(CLI::App& app, Options* o) {
  app.description("The normal problem per patch against the exact solver on case A-2.2.");
  tools::option(app, "--cases", &o->cases, "A-2.2 states (CSV as test/data/profiles/)");
  tools::option(app, "--load", &o->load, "vertical wheel load [N]");
  tools::option(app, "--G", &o->G, "shear modulus [Pa]");
  tools::option(app, "--nu", &o->nu, "Poisson ratio");
  tools::option(app, "--grid", &o->grid, "exact grid nx = ny");
  tools::option(app, "--min-ridge", &o->min_ridge, "ContactSearchOptions::min_ridge [m]");
  tools::option(app, "--gap-samples", &o->gap_samples, "ContactSearchOptions::gap_samples");
  app.add_flag_callback(
      "--no-continuous-region", [o] { o->continuous_region = false; },
      "NormalOptions::continuous_region = false (its rule before it became the default)");
}

double percent(double a, double b) {
  return 100.0 * (a / b - 1.0);
}

int run(const Options& o) {
  ContactSearchOptions so;
  so.min_ridge = o.min_ridge;
  so.gap_samples = o.gap_samples;
  const ContactSearch search{WheelsetTrackData{}, so};
  std::printf(
      "*: the method's message flags a gap that turns concave under the patch; lumps: a patch "
      "merged across a ridge\n\n");
  std::printf(
      "| y mm | patch | angle | method | fn N | fn err %% | pmax GPa | pmax err %% | "
      "extent mm (exact) | share (exact) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const A22State& state : readA22States(o.cases)) {
    if (state.side != WheelSide::kRight) continue;
    WheelsetPose pose = a22Pose(state);  // the benchmark's axes turned to ours
    WheelContactGeometry geo;
    for (int k = 0; k < 4; ++k) {  // down to first touch
      geo = search.search(WheelSide::kRight, pose);
      if (geo.closest < 0) break;
      pose.z -= geo.candidates[geo.closest].vertical_gap;
    }
    NormalOptions no;
    no.continuous_region = o.continuous_region;
    const WheelNormal w = solveWheelLoad(geo, o.load, o.G, o.nu, no);
    if (w.status != NormalStatus::kOk) {
      std::printf("| %.1f | - | - | %s | | | | | | |\n", state.y_mm, w.message.c_str());
      continue;
    }
    int loaded = 0;
    for (const NormalPatch& p : w.patches) loaded += p.fn > 0.0;
    std::vector<double> split;
    if (loaded > 1) split = exactWheelLoad(geo, o.load, o.G, o.nu, o.grid, w.vertical_approach);
    double total = 0.0, exact_total = 0.0;
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      total += w.patches[i].fn;
      if (!split.empty()) exact_total += split[i];
    }
    for (std::size_t i = 0; i < w.patches.size(); ++i) {
      const NormalPatch& p = w.patches[i];
      if (p.fn <= 0.0) continue;
      // A merged patch against the exact solution on the merged gap function.
      int first = static_cast<int>(i), last = first;
      for (std::size_t k = 0; k < w.patches.size(); ++k)
        if (w.patches[k].merged_into == static_cast<int>(i)) {
          first = std::min(first, static_cast<int>(k));
          last = std::max(last, static_cast<int>(k));
        }
      const ContactCandidate c =
          last > first ? mergeCandidates(geo.candidates, first, last, static_cast<int>(i))
                       : geo.candidates[i];
      const ExactPatch e = exactPatchNormal(c, p.approach, o.G, o.nu, o.grid, o.grid);
      char share[64] = "";
      if (!split.empty())
        std::snprintf(share, sizeof share, "%.3f (%.3f)", p.fn / total, split[i] / exact_total);
      std::printf(
          "| %.1f%s | %zu | %.3f | %s | %.0f | %+.1f | %.2f | %+.1f | %.2f..%.2f (%.2f..%.2f) "
          "| %s |\n",
          state.y_mm, p.message.find("concave") == std::string::npos ? "" : " *", i,
          geo.candidates[i].contact_angle,
          last > first                       ? "lumps"
          : p.method == NormalMethod::kHertz ? "Hertz"
                                             : "strips",
          p.fn, percent(p.fn, e.fn), p.pmax * 1e-9, percent(p.pmax, e.pmax), p.eta_min * 1e3,
          p.eta_max * 1e3, e.eta_min * 1e3, e.eta_max * 1e3, share);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("normal_accuracy", argc, argv, addOptions, run);
}
