// patch_frequency: the frequency response of the creep-force models to a harmonic lateral creepage
// on real patches, Manchester A-2.2's right wheel: the gauge corner at y = 5 mm and the tread at
// y = 0.5 mm (validation/patch_harmonic.hpp), against the exact transient solver on each patch's
// own gap. Per patch, lambda/a and model: the complex response of fs, fx and mz to eta over the
// exact steady response (fs^ / fs_steady, fx^ / fs_steady, mz^ / mz_steady), the models on the
// equivalent ellipse and on the strips. The patch's own creepages are left out: eta alone, small
// (linear, full adhesion), unless --partial, which adds the case's creepages halved as a mean
// (partial slip) and makes the harmonic 10 % of that mean eta. doc/validation.md.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "validation/patch_harmonic.hpp"

using namespace wheel_rail_contact;

namespace {

const PatchGeometry kGeometries[] = {PatchGeometry::kEllipse, PatchGeometry::kStrips,
                                     PatchGeometry::kExactStrips};

struct Options {
  std::string cases = "test/data/profiles/a22_cases.csv";
  std::string out = "doc/data/patch_freq.csv";
  int exact_mx = 32, exact_my = 24, nx = 20;
  double mu = 0.3;
  std::vector<double> lambdas = {1, 1.5, 2, 3, 5, 10, 20, 50, 100};
  bool partial = false;
  std::string fastsim;  // empty: each model's own variant (calibrated nss, classic baselines)
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Frequency response to a harmonic lateral creepage on A-2.2's gauge-corner (y = 5 mm) and "
      "tread (y = 0.5 mm) patches: nss, shen-li, steady against the exact transient solver.");
  tools::option(app, "--cases", &o->cases, "the benchmark's wheelset states (a22_cases.csv)");
  tools::option(app, "--out", &o->out, "the table, one row per patch, lambda/a, model, geometry");
  tools::option(app, "--exact-mx", &o->exact_mx, "exact grid: elements along x per patch");
  tools::option(app, "--exact-my", &o->exact_my, "exact grid: elements across per patch");
  tools::option(app, "--nx", &o->nx, "FastSim mesh nx = ny");
  tools::option(app, "--mu", &o->mu, "friction coefficient");
  tools::option(app, "--lambdas", &o->lambdas, "wavelengths over the equivalent ellipse's a");
  tools::option(app, "--fastsim", &o->fastsim,
                "classic or calibrated for every model; empty: each model's own (nss calibrated, "
                "steady and shen-li classic)");
  tools::flag(app, "--partial", &o->partial,
              "the case's creepages halved as a mean (partial slip), harmonic 10 % of its eta");
}

int run(const Options& o) {
  std::ofstream out = tools::writeFile(o.out);
  out << "patch,method,a_mm,b_mm,fn_N,exact_fn_N,amplitude,mean_xi,mean_eta,mean_phi_per_m,"
         "exact_fs_steady_N,exact_mz_steady_Nm,lambda_over_a,model,geometry,fs_re,fs_im,fx_re,"
         "fx_im,mz_re,mz_im,error\n";
  const std::pair<double, ContactZone> patches[] = {{5.0, ContactZone::kGaugeCorner},
                                                    {0.5, ContactZone::kTread}};
  for (const auto& pz : patches) {
    const RealPatch patch = a22RightPatch(o.cases, pz.first, pz.second, o.exact_mx, o.exact_my);
    const Creepages mean = o.partial
                               ? Creepages{0.5 * patch.creepages.xi, 0.5 * patch.creepages.eta,
                                           0.5 * patch.creepages.phi}
                               : Creepages{};
    const double amplitude = o.partial ? 0.1 * std::abs(mean.eta) : 0.0;
    const double amp0 = patchHarmonicScene(patch, 10.0, o.mu, amplitude, mean).amplitude;
    const PatchResponse gain = exactSteadyResponse(patch, amp0, mean, o.mu);
    const double fs0 = gain.fs.real(), mz0 = gain.mz.real();
    const NormalPatch& n = patch.normal;
    std::printf(
        "%s: %s, a %.2f mm, b %.2f mm, fn %.0f N (exact %.0f N), eta amplitude %.3g, "
        "exact steady dfs/deta %.4g N, dmz/deta %.4g N m, exact dq %.3f a\n",
        patch.name.c_str(), n.method == NormalMethod::kHertz ? "hertz" : "strips", 1e3 * n.a,
        1e3 * n.b, n.fn, patch.exact.fn, amp0, fs0, mz0, patch.exact.grid.dx / n.a);
    // Per model and geometry: its steady gain over exact's, and the worst over lambda/a >= 2 of
    // |C - C_exact| (over exact's steady gain) and of |C / C_own - C_exact / C_exact,steady| (the
    // response's shape, each over its own steady gain: steady FastSim's on the same geometry).
    struct Worst {
      double gain = 0.0, absolute = 0.0, shape = 0.0;
    };
    std::map<std::string, Worst> worst;
    for (double l : o.lambdas) {
      const PatchHarmonicScene scene = patchHarmonicScene(patch, l, o.mu, amplitude, mean);
      const std::vector<StepOutput> exact = runExactHarmonic(patch, scene, o.mu);
      int failed = 0;
      for (const StepOutput& s : exact) failed += s.status != StepStatus::kOk;
      if (failed) std::fprintf(stderr, "  l/a %g: %d exact steps not converged\n", l, failed);
      auto row = [&](const char* model, const char* geometry, const std::vector<StepOutput>& f) {
        const PatchResponse r = harmonicResponse(scene, f);
        char line[512];
        std::snprintf(line, sizeof line,
                      "%s,%s,%.4f,%.4f,%.1f,%.1f,%.4g,%.4g,%.4g,%.4g,%.6g,%.6g,%.4g,%s,%s,%.5f,"
                      "%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n",
                      patch.name.c_str(), n.method == NormalMethod::kHertz ? "hertz" : "strips",
                      1e3 * n.a, 1e3 * n.b, n.fn, patch.exact.fn, scene.amplitude, mean.xi,
                      mean.eta, mean.phi, fs0, mz0, scene.lambda_over_a, model, geometry,
                      r.fs.real() / fs0, r.fs.imag() / fs0, r.fx.real() / fs0, r.fx.imag() / fs0,
                      r.mz.real() / mz0, r.mz.imag() / mz0, patchHarmonicError(scene, f, exact));
        out << line;
        return r.fs / fs0;
      };
      const std::complex<double> ce = row("exact", "grid", exact);
      std::printf("  l/a %6.3g exact %6.3f %6.1f deg |", scene.lambda_over_a, std::abs(ce),
                  180.0 / M_PI * std::arg(ce));
      for (const PatchGeometry g : kGeometries) {
        std::map<std::string, std::complex<double>> c;
        for (const char* m : {"steady", "nss", "shen-li"}) {
          ContactParameters p;
          p.model = m;
          p.nx = p.ny = o.nx;
          p.mu = o.mu;
          if (!o.fastsim.empty()) setParameter(&p, "fastsim", o.fastsim);
          c[m] = row(m, toString(g), runModelHarmonic(patch, scene, p, g));
          if (scene.lambda_over_a < 1.99) continue;
          Worst& w = worst[std::string(m) + " " + toString(g)];
          w.gain = std::abs(c["steady"]);
          w.absolute = std::max(w.absolute, std::abs(c[m] - ce));
          w.shape = std::max(w.shape, std::abs(c[m] / c["steady"] - ce));
        }
        std::printf(" %s nss %5.3f %6.1f", toString(g), std::abs(c["nss"]),
                    180.0 / M_PI * std::arg(c["nss"]));
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    std::printf(
        "  over lambda/a >= 2: steady gain / exact's; worst |C - C_exact|; worst "
        "|C/C_own steady - C_exact/C_exact steady| (all over exact's steady gain)\n");
    for (const auto& kv : worst)
      std::printf("    %-22s %6.3f %6.3f %6.3f\n", kv.first.c_str(), kv.second.gain,
                  kv.second.absolute, kv.second.shape);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("patch_frequency", argc, argv, addOptions, run);
}
