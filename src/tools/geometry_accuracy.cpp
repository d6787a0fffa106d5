// Accuracy of the FastSim models under a changing patch shape (per-step a, b) against the exact
// half-space solver honouring the same per-step geometry: the scenes of
// validation/varying_geometry.hpp. Writes <out>/geometry_<scene>.csv (the force histories) and
// <out>/varying_geometry_errors.csv (RMS error over the peak exact force, last period), and prints
// the latter. doc/varying_geometry.md.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "validation/varying_geometry.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "doc/data";
  int grid = 30;  ///< exact grid nx = ny
  int n = 20;     ///< FastSim mesh nx = ny
};

struct Variant {
  const char* label;
  const char* model;
  const char* mesh;
};
const Variant kVariants[] = {{"steady", "steady", "fixed"},
                             {"shen-li_fixed", "shen-li", "fixed"},
                             {"shen-li_adaptive", "shen-li", "adaptive"},
                             {"nss_fixed", "nss", "fixed"},
                             {"nss_adaptive", "nss", "adaptive"},
                             {"auto", "auto", "fixed"}};

void addOptions(CLI::App& app, Options* o) {
  app.description("The FastSim models under a changing patch shape against the exact solver.");
  tools::option(app, "--out", &o->out, "output folder (must exist)");
  tools::option(app, "--grid", &o->grid, "exact grid nx = ny");
  tools::option(app, "--n", &o->n, "FastSim mesh nx = ny");
}

int run(const Options& o) {
  tools::requireFolder(o.out);
  // Rows one exact element apart (the grid covers the patch at fz_max = 1.8 Fz).
  const double step = 2.2 * 0.02 * std::cbrt(1.8) / o.grid;
  std::vector<PaperScene> scenes;
  for (double l : {5.0, 10.0, 20.0}) scenes.push_back(harmonicAOverBScene(l, step));
  scenes.push_back(stepAOverBScene(step));
  std::ofstream errors = tools::writeFile(o.out + "/varying_geometry_errors.csv");
  errors << "scene,model,rms_over_peak\n";
  std::printf("%-16s", "scene");
  for (const Variant& v : kVariants) std::printf(" %16s", v.label);
  std::printf("\n");
  for (const PaperScene& s : scenes) {
    ContactParameters p = s.params;
    p.model = "exact";
    p.nx = p.ny = o.grid;
    auto exactModel = makeContactModel(p);
    const std::vector<StepOutput> exact = runScene(*exactModel, s.rows);
    std::vector<std::vector<StepOutput>> runs;
    std::printf("%-16s", s.name.c_str());
    for (const Variant& v : kVariants) {
      ContactParameters q = s.params;
      q.model = v.model;
      q.mesh = v.mesh;
      q.nx = q.ny = o.n;
      auto model = makeContactModel(q);
      runs.push_back(runScene(*model, s.rows));
      const double e = sceneError(s, runs.back(), exact).rmsOverPeak;
      errors << s.name << "," << v.label << "," << e << "\n";
      std::printf(" %16.4f", e);
    }
    std::printf("\n");
    std::ofstream series = tools::writeFile(o.out + "/geometry_" + s.name + ".csv");
    series << "q_over_a0,a_over_b,fx_exact,fy_exact";
    for (const Variant& v : kVariants) series << ",fx_" << v.label << ",fy_" << v.label;
    series << "\n";
    for (size_t k = 0; k < s.rows.size(); ++k) {
      const ScenarioRow& r = s.rows[k];
      char line[64];
      std::snprintf(line, sizeof line, "%.6g,%.6g", r.t * r.V / s.params.a0, r.a / r.b);
      series << line;
      for (const StepOutput& f : {exact[k]}) series << "," << f.fx << "," << f.fy;
      for (const auto& run : runs) series << "," << run[k].fx << "," << run[k].fy;
      series << "\n";
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("geometry_accuracy", argc, argv, addOptions, run);
}
