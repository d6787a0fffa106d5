// speed_accuracy: cost per step against accuracy for every model and mesh (issue 6). Scenes:
//   freq_<kind>_l<lambda/a>  one small harmonic creepage, kinds 11, 22, 23, lambda/a 1 ... 100,
//                            reference = linear response of the exact solver in the frequency
//                            domain (--grid, harmonic_scenes.hpp)
//   combined<1-3>            the paper's eqs. 16-18, reference = exact solver at --grid
//   load_xi<xi>_l<lambda/a>  varying load (section 4.2), reference = exact solver at --load-grid
// Error per scene: RMS |F - F_ref| over the last period / peak |F_ref| there (sceneError). Cost per
// scene: least thread CPU time per step over --repeats (and at least 20 ms of) passes, each from a
// fresh state, after the scored pass (the exact solver: that pass alone), and over --rounds sweeps
// of every model (retime); per model and mesh the
// mean over the scenes, so that auto pays for the scenes where it runs NSS-FastSim and gains on
// those where it runs steady FastSim (nss_share: its share of NSS-FastSim steps per scene).
// The paper scenes' exact histories are the slow part (15 min at 40/30 on a busy 2-core machine):
// cached in <out>/speed_accuracy_reference.csv, reused when its key line matches, rebuilt on
// --refresh.
// Writes <out>/speed_accuracy.csv (one row per model and mesh) and speed_accuracy_scenes.csv.
// Real-profile cases (--parts patches or all): Manchester A-2.2's right-wheel gauge corner
// (y = 5 mm) and tread (y = 0.5 mm) patches (validation/patch_harmonic.hpp), each model on the
// patch as its equivalent ellipse with Hertz's pressure and on its strips, and the exact solver
// at coarser grids, against the exact transient solver at --patch-grid; written to
// <out>/speed_accuracy_patches.csv, one row per model, mesh, geometry and scene.
// Options: speed_accuracy --help.
// LIST: NAME[:MESH[:FASTSIM]],... (mesh fixed when left out), by default
// steady,shen-li,nss:fixed,nss:adaptive,exact,auto:adaptive; a model this build lacks is skipped,
// with a note. auto runs once per tolerance, on the mesh it chooses. Every FastSim model (all but
// exact) runs once per variant of --fastsim (classic,calibrated by default) unless its spec names
// one, and the variant is set on every run and written in every row: the parameters' default
// variant may change, the chart's rows must not.
// --set passes any ContactParameters field (setParameter) to every model run, e.g. a tolerance;
// the exact reference keeps the scene's own parameters.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/models/auto_model.hpp"
#include "tool_options.hpp"
#include "validation/harmonic_scenes.hpp"
#include "validation/patch_harmonic.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "doc/data";
  // auto runs once per tolerance (--tolerances) on the mesh it chooses.
  std::vector<std::string> models = {"steady",       "shen-li", "nss:fixed",
                                     "nss:adaptive", "exact",   "auto:adaptive"};
  std::vector<int> meshes = {5, 10, 20, 30, 40}, exactMeshes = {10, 20};
  // auto picks its own mesh: it runs once per tolerance instead of once per mesh.
  std::vector<double> tolerances = {0.1, 0.05};
  std::vector<std::string> fastsims = {"classic", "calibrated"};  // variants of every FastSim model
  int grid = 40, loadGrid = 30, periods = 3, repeats = 7, rounds = 3;
  std::vector<std::string> sets;                               // --set NAME=VALUE, as given
  std::vector<std::pair<std::string, std::string>> overrides;  // the same, split
  bool refresh = false;
  std::string parts = "all";  // all | paper (the elliptic scenes) | patches (real profiles)
  std::string cases = "test/data/profiles/a22_cases.csv";
  int patchGrid = 40;                           // exact reference grid mx (my = 3/4 mx)
  std::vector<int> patchExactGrids = {12, 20};  // the exact model's points on the chart
};

struct Scene {
  std::string family;  // freq | combined | load
  PaperScene scene;
  std::vector<StepOutput> reference;
};

const double kLambdas[] = {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0};  // lambda/a of the sweep

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

// Row spacing V dt of the paper scenes [m]: the exact reference's element length (its scheme
// needs dq = dx), as accuracy_report uses.
double combinedStep(const Options& o) {
  return 2.2 * 0.02 / o.grid;
}
double loadStep(const Options& o) {
  return 2.2 * 0.02 * std::cbrt(1.25) / o.loadGrid;
}

std::vector<Scene> harmonicScenes(const Options& o) {
  std::vector<Scene> out;
  for (CreepageKind kind : kCreepageKinds) {
    // The sweep's patch is circular and nu = 0.28, as harmonicScene's material.
    const NonSteadyCoefficients exact(kind, 1.0, 0.28, o.grid, o.grid);
    for (double l : kLambdas) {
      const HarmonicScene h = harmonicScene(kind, l, combinedStep(o));
      out.push_back({"freq", h.scene, harmonicResponse(h, exact.at(l))});
    }
    std::cerr << "frequency reference C" << coefficientName(kind) << " done\n";
  }
  return out;
}

std::vector<Scene> paperScenes(const Options& o) {
  std::vector<Scene> out;
  for (int c = 1; c <= 3; ++c)
    out.push_back({"combined", combinedCreepageScene(c, o.periods, combinedStep(o)), {}});
  for (double xi : {0.002, 0.01, 0.05, 0.1})
    for (double l : {5.0, 15.0, 40.0})
      out.push_back({"load", varyingLoadScene(xi, l, o.periods, loadStep(o)), {}});
  return out;
}

// ---- the cached exact histories of the paper scenes --------------------------------------------

std::string cachePath(const Options& o) {
  return o.out + "/speed_accuracy_reference.csv";
}

std::string cacheKey(const Options& o) {
  return "# exact reference: grid " + std::to_string(o.grid) + ", load grid " +
         std::to_string(o.loadGrid) + ", periods " + std::to_string(o.periods);
}

// Fills every scene's reference from the cache; false if the key or any scene's length differs.
// The key cannot see a change to the exact solver itself: --refresh after one.
bool readCache(const Options& o, std::vector<Scene>* scenes) {
  std::ifstream in(cachePath(o));
  std::string line;
  if (!std::getline(in, line) || line != cacheKey(o) || !std::getline(in, line)) return false;
  std::map<std::string, std::vector<StepOutput>> hist;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line, ',');
    if (f.size() != 4) return false;
    StepOutput r;
    r.fx = std::stod(f[2]);
    r.fy = std::stod(f[3]);
    hist[f[0]].push_back(r);
  }
  for (Scene& s : *scenes) {
    std::vector<StepOutput>& h = hist[s.scene.name];
    if (h.size() != s.scene.rows.size()) return false;
    s.reference = h;
  }
  return true;
}

void writeCache(const Options& o, const std::vector<Scene>& scenes) {
  std::ofstream out = tools::writeFile(cachePath(o));
  out << cacheKey(o) << "\nscene,row,fx,fy\n";
  for (const Scene& s : scenes)
    for (size_t k = 0; k < s.reference.size(); ++k) {
      char line[160];
      std::snprintf(line, sizeof line, "%s,%zu,%.9g,%.9g\n", s.scene.name.c_str(), k,
                    s.reference[k].fx, s.reference[k].fy);
      out << line;
    }
}

void computeReferences(const Options& o, std::vector<Scene>* scenes) {
  for (Scene& s : *scenes) {
    ContactParameters p = s.scene.params;
    p.model = "exact";
    p.nx = p.ny = s.family == "load" ? o.loadGrid : o.grid;
    s.reference = runScene(*makeContactModel(p), s.scene.rows);
    std::cerr << "exact reference " << s.scene.name << " done\n";
  }
}

// ---- one model on one mesh ----------------------------------------------------------------------

struct Variant {
  std::string model, mesh;
  std::string fastsim;  // classic | calibrated; kNoFastSim for the exact solver
  int n = 0;
  double tolerance = 0.0;  // auto only (0: the parameter's default)
};

const char* const kNoFastSim = "-";

struct Result {
  Variant v;
  double nsPerStep = 0.0;      // mean over the scenes of nsPerScene
  std::vector<double> errors;  // per scene, in scene order
  std::vector<double> nsPerScene;
  std::vector<double> nssShare;  // auto only: share of each scene's steps that ran NSS-FastSim
};

ContactParameters paramsFor(const Options& o, const Variant& v, const PaperScene& s) {
  ContactParameters p = s.params;
  p.model = v.model;
  p.mesh = v.mesh;
  if (v.n > 0) p.nx = p.ny = v.n;  // auto chooses its own (n = 0)
  for (const auto& kv : o.overrides) setParameter(&p, kv.first, kv.second);
  if (v.tolerance > 0.0) p.tolerance = v.tolerance;
  if (v.fastsim != kNoFastSim) setParameter(&p, "fastsim", v.fastsim);
  return p;
}

// CPU time of this thread [ns]: unlike wall time, it leaves out the time other processes on a
// shared machine hold the core, which is most of the noise of a wall-clock measurement here.
double threadCpuNs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e9 * ts.tv_sec + ts.tv_nsec;
}

// One pass over the rows from a fresh state; the forces go to a sink so that nothing is elided and
// nothing is stored (an output vector would add its own cost to every step).
double timedPass(ContactModel& model, const std::vector<ScenarioRow>& rows) {
  static volatile double sink = 0.0;
  model.reset();
  const double t0 = threadCpuNs();
  for (size_t k = 0; k < rows.size(); ++k) sink = sink + model.step(stepInputAt(rows, k)).fx;
  return threadCpuNs() - t0;
}

// The scored pass: outputs kept, and for auto the steps that ran NSS-FastSim counted.
std::vector<StepOutput> recordedPass(ContactModel& model, const std::vector<ScenarioRow>& rows,
                                     double* nssShare) {
  const auto* automatic = dynamic_cast<const AutoModel*>(&model);
  model.reset();
  std::vector<StepOutput> out;
  out.reserve(rows.size());
  size_t nss = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    out.push_back(model.step(stepInputAt(rows, k)));
    nss += automatic && automatic->nonSteady();
  }
  *nssShare = automatic ? double(nss) / rows.size() : 1.0;
  return out;
}

// Least CPU ns per step of one scene over at least `repeats` passes and 20 ms: on a shared
// (virtual) machine the host's interruptions only ever add time, and they made medians of the same
// code differ by up to 1.7x between runs. A model whose scored pass alone took `slow` (the exact
// solver) is timed by that pass.
double timePerStep(const Options& o, ContactModel& model, const std::vector<ScenarioRow>& rows,
                   double scoredNs) {
  constexpr double slow = 1e8;
  if (scoredNs > slow) return scoredNs / rows.size();
  std::vector<double> samples;
  double total = 0.0;
  for (int r = 0; r < o.repeats || (total < 2e7 && r < 200); ++r) {
    samples.push_back(timedPass(model, rows));
    total += samples.back();
  }
  return *std::min_element(samples.begin(), samples.end()) / rows.size();
}

Result evaluate(const Options& o, const Variant& v, const std::vector<Scene>& scenes) {
  Result res{v, 0.0, {}, {}, {}};
  for (const Scene& s : scenes) {
    auto model = makeContactModel(paramsFor(o, v, s.scene));
    if (const auto* a = dynamic_cast<const AutoModel*>(model.get()))
      res.v.n = std::max(res.v.n, a->meshSize());  // the finest it chose over the scenes
    double share = 1.0;
    const double t0 = threadCpuNs();
    const std::vector<StepOutput> out = recordedPass(*model, s.scene.rows, &share);
    const double scoredNs = threadCpuNs() - t0;
    res.errors.push_back(sceneError(s.scene, out, s.reference).rmsOverPeak);
    res.nssShare.push_back(share);
    res.nsPerScene.push_back(timePerStep(o, *model, s.scene.rows, scoredNs));
    res.nsPerStep += res.nsPerScene.back() / scenes.size();
  }
  return res;
}

// Rounds 2 ... --rounds time every scene of every variant again, the whole sweep each round, so
// that a slow spell of the host (seconds long here) falls on one round of a scene rather than on
// all its passes; the least stands. The exact solver keeps the time of its one scored pass.
void retime(const Options& o, const std::vector<Scene>& scenes, std::vector<Result>* results) {
  for (int round = 1; round < o.rounds; ++round) {
    for (Result& r : *results) {
      if (r.v.model == "exact") continue;
      Variant v = r.v;
      if (v.model == "auto") v.n = 0;  // it chooses its own mesh, as in evaluate()
      r.nsPerStep = 0.0;
      for (size_t k = 0; k < scenes.size(); ++k) {
        auto model = makeContactModel(paramsFor(o, v, scenes[k].scene));
        const double ns = timePerStep(o, *model, scenes[k].scene.rows, 0.0);
        r.nsPerScene[k] = std::min(r.nsPerScene[k], ns);
        r.nsPerStep += r.nsPerScene[k] / scenes.size();
      }
    }
  }
}

std::vector<Variant> variants(const Options& o) {
  std::vector<Variant> out;
  for (const std::string& spec : o.models) {
    const std::vector<std::string> f = split(spec, ':');
    if (f.empty() || f.size() > 3)
      throw std::invalid_argument("--models: bad entry '" + spec + "'");
    const std::string mesh = f.size() > 1 ? f[1] : "fixed";
    std::vector<std::string> kinds = f.size() > 2 ? std::vector<std::string>{f[2]} : o.fastsims;
    if (f.size() > 2 && f[2] != "classic" && f[2] != "calibrated")
      throw std::invalid_argument("--models: FASTSIM is classic or calibrated, in '" + spec + "'");
    if (f[0] == "exact") kinds = {kNoFastSim};
    for (const std::string& fastsim : kinds) {
      if (f[0] == "auto") {
        for (double t : o.tolerances) out.push_back({f[0], mesh, fastsim, 0, t});
        continue;
      }
      for (int n : f[0] == "exact" ? o.exactMeshes : o.meshes)
        out.push_back({f[0], mesh, fastsim, n});
    }
  }
  return out;
}

// ---- real-profile cases -------------------------------------------------------------------------

constexpr double kPatchMu = 0.3;  // the benchmark's friction

struct PatchCase {
  std::string name;  // <patch>_<scene>
  const RealPatch* patch;
  PatchHarmonicScene scene;
  bool held = false;  // creepages held: scored over mu fn (exact) instead of the peak force
};

// The scenes of one patch at its exact grid's step: the case's creepages held (partial slip, up to
// saturation on the corner; scored once steady), a small harmonic eta alone at lambda/a 5 and 20
// (linear), and eta harmonic by 10 % about the case's creepages halved at lambda/a 5.
std::vector<PatchCase> patchCases(const RealPatch* patch, const std::string& name) {
  const Creepages& c = patch->creepages;
  const Creepages half{0.5 * c.xi, 0.5 * c.eta, 0.5 * c.phi};
  std::vector<PatchCase> out;
  PatchHarmonicScene held = patchHarmonicScene(*patch, 2.0, kPatchMu, 0.0, c);
  for (Creepages& x : held.creepages) x = c;
  out.push_back({name + "_held", patch, held, true});
  for (double l : {5.0, 20.0}) {
    char tag[32];
    std::snprintf(tag, sizeof tag, "_linear_l%g", l);
    out.push_back({name + tag, patch, patchHarmonicScene(*patch, l, kPatchMu)});
  }
  out.push_back({name + "_partial_l5", patch,
                 patchHarmonicScene(*patch, 5.0, kPatchMu, 0.1 * std::abs(half.eta), half)});
  return out;
}

// The real-profile scenes on an exact grid mx x 3/4 mx: the gauge corner at 5 mm (Hertz: ellipse
// and strips alike), the tread at 0.5 mm (non-Hertzian; our patch narrower than the exact one,
// doc/true_patch.md) and the centred tread at 0 mm (a/b 0.26: where the strips matter most).
std::vector<PatchCase> patchScenes(const Options& o, int mx,
                                   std::vector<std::unique_ptr<RealPatch>>* patches) {
  const std::pair<double, ContactZone> where[] = {
      {5.0, ContactZone::kGaugeCorner}, {0.5, ContactZone::kTread}, {0.0, ContactZone::kTread}};
  std::vector<PatchCase> out;
  for (const auto& w : where) {
    patches->push_back(
        std::make_unique<RealPatch>(a22RightPatch(o.cases, w.first, w.second, mx, mx * 3 / 4)));
    for (PatchCase& c : patchCases(patches->back().get(), patches->back()->name)) out.push_back(c);
  }
  return out;
}

// A force history's mean and fundamental (at the scene's frequency) over its last period: the
// measure that compares runs at different steps (the exact solver at a coarser grid rolls its own
// element length). Error: the RMS of their difference, sqrt(|d mean|^2 + |d fundamental|^2 / 2),
// over the reference's peak |(fx, fs)| in its last period, or, with the creepages held, over
// mu fn (the benchmark's measure: a held force may be small against the patch's capacity).
struct Summary {
  std::complex<double> mx, ms, fx, fs;  // means and fundamentals of fx, fs
  double peak = 0.0;
};

Summary summarize(const PatchHarmonicScene& s, const std::vector<StepOutput>& f) {
  const int n = s.period_steps, first = static_cast<int>(f.size()) - n;
  Summary r;
  for (int k = 0; k < n; ++k) {
    const std::complex<double> w = std::polar(2.0 / n, -2.0 * M_PI * k / n);
    const StepOutput& o = f[first + k];
    r.mx += o.fx / n;
    r.ms += o.fy / n;
    r.fx += o.fx * w;
    r.fs += o.fy * w;
    r.peak = std::max(r.peak, std::hypot(o.fx, o.fy));
  }
  return r;
}

double summaryError(const Summary& m, const Summary& ref, const PatchCase& c) {
  const double d2 = std::norm(m.mx - ref.mx) + std::norm(m.ms - ref.ms) +
                    0.5 * (std::norm(m.fx - ref.fx) + std::norm(m.fs - ref.fs));
  const double norm = c.held ? kPatchMu * c.patch->exact.fn : ref.peak;
  return std::sqrt(d2) / std::max(norm, 1e-300);
}

// One pass of a model over a scene's steps from a fresh state; CPU ns.
double timedPatchPass(ContactModel& model, const RealPatch& patch, const PatchHarmonicScene& s,
                      PatchGeometry g, std::vector<StepOutput>* out) {
  static volatile double sink = 0.0;
  model.reset();
  StepInput in;
  in.V = 1.0;
  in.dt = s.dq;
  in.fz = patch.normal.fn;
  in.a = patch.normal.a;
  in.b = patch.normal.b;
  in.shape = g == PatchGeometry::kStrips ? &patch.shape : nullptr;
  const double t0 = threadCpuNs();
  for (const Creepages& c : s.creepages) {
    in.xi = c.xi;
    in.eta = c.eta;
    in.phi = c.phi;
    const StepOutput o = model.step(in);
    if (out) out->push_back(o);
    sink = sink + o.fx;
  }
  return threadCpuNs() - t0;
}

ContactParameters patchParams(const Options& o, const Variant& v, const RealPatch& patch) {
  PaperScene base;
  base.params.G = patch.G;
  base.params.nu = patch.nu;
  base.params.mu = kPatchMu;
  const NormalPatch& n = patch.normal;
  base.params.b0 = n.b;
  base.params.a0 = std::min(std::max(n.a, kKalkerMinAOverB * n.b), kKalkerMaxAOverB * n.b);
  base.params.fz0 = n.fn;
  base.params.fz_max = 0.0;
  return paramsFor(o, v, base);
}

void patchPart(const Options& o, const std::vector<Variant>& vs) {
  std::cerr << "real-profile cases: A-2.2 patches, exact reference " << o.patchGrid << "x"
            << o.patchGrid * 3 / 4 << "\n";
  std::vector<std::unique_ptr<RealPatch>> patches;
  std::vector<PatchCase> cases = patchScenes(o, o.patchGrid, &patches);
  std::vector<Summary> refs;
  for (const PatchCase& c : cases) {
    refs.push_back(summarize(c.scene, runExactHarmonic(*c.patch, c.scene, kPatchMu)));
    std::cerr << "exact reference " << c.name << " done\n";
  }
  std::ofstream out = tools::writeFile(o.out + "/speed_accuracy_patches.csv");
  out << "model,mesh,fastsim,nx,ny,tolerance,geometry,scene,error,ns_per_step\n";
  auto write = [&](const Variant& v, int ny, const char* geometry, const PatchCase& c, double err,
                   double ns) {
    char line[256];
    std::snprintf(line, sizeof line, "%s,%s,%s,%d,%d,%g,%s,%s,%.5f,%.4g\n", v.model.c_str(),
                  v.mesh.c_str(), v.fastsim.c_str(), v.n, ny, v.tolerance, geometry, c.name.c_str(),
                  err, ns);
    out << line;
  };
  // The exact solver on coarser grids, each on its own grid's step: one timed pass.
  for (int mx : o.patchExactGrids) {
    std::vector<std::unique_ptr<RealPatch>> own_patches;
    const std::vector<PatchCase> own = patchScenes(o, mx, &own_patches);
    for (size_t k = 0; k < own.size(); ++k) {
      const double t0 = threadCpuNs();
      const std::vector<StepOutput> f = runExactHarmonic(*own[k].patch, own[k].scene, kPatchMu);
      const double ns = (threadCpuNs() - t0) / f.size();
      write({"exact", "grid", kNoFastSim, mx}, mx * 3 / 4, "grid", own[k],
            summaryError(summarize(own[k].scene, f), refs[k], cases[k]), ns);
    }
    std::cerr << "exact " << mx << "x" << mx * 3 / 4 << " done\n";
  }
  for (const Variant& v : vs) {
    if (v.model == "exact") continue;
    for (const PatchGeometry g : {PatchGeometry::kEllipse, PatchGeometry::kStrips}) {
      for (size_t k = 0; k < cases.size(); ++k) {
        const PatchCase& c = cases[k];
        std::unique_ptr<ContactModel> model;
        try {
          model = makeContactModel(patchParams(o, v, *c.patch));
        } catch (const std::invalid_argument& e) {
          std::cerr << "skipping " << v.model << " on " << c.name << ": " << e.what() << "\n";
          continue;
        }
        std::vector<StepOutput> f;
        timedPatchPass(*model, *c.patch, c.scene, g, &f);
        double best = 1e300, total = 0.0;
        for (int r = 0; r < o.repeats || (total < 2e7 && r < 200); ++r) {
          const double ns = timedPatchPass(*model, *c.patch, c.scene, g, nullptr);
          best = std::min(best, ns);
          total += ns;
        }
        Variant shown = v;
        if (const auto* a = dynamic_cast<const AutoModel*>(model.get())) shown.n = a->meshSize();
        write(shown, shown.n, toString(g), c, summaryError(summarize(c.scene, f), refs[k], c),
              best / c.scene.creepages.size());
      }
    }
    std::cerr << "patches: " << v.model << ":" << v.mesh << ":" << v.fastsim << " " << v.n
              << " done\n";
  }
}

// ---- output -------------------------------------------------------------------------------------

double worstOf(const Result& r, const std::vector<Scene>& scenes, const std::string& family) {
  double w = 0.0;
  for (size_t k = 0; k < scenes.size(); ++k)
    if (family.empty() || scenes[k].family == family) w = std::max(w, r.errors[k]);
  return w;
}

void writeResults(const Options& o, const std::vector<Result>& results,
                  const std::vector<Scene>& scenes) {
  std::ofstream table = tools::writeFile(o.out + "/speed_accuracy.csv"),
                per = tools::writeFile(o.out + "/speed_accuracy_scenes.csv");
  table << "model,mesh,fastsim,nx,ny,tolerance,ns_per_step,worst_error,mean_error,worst_freq,"
           "worst_combined,worst_load\n";
  per << "model,mesh,fastsim,nx,ny,tolerance,scene,family,error,ns_per_step,nss_share\n";
  for (const Result& r : results) {
    double sum = 0.0;
    for (double e : r.errors) sum += e;
    char line[256];
    std::snprintf(line, sizeof line, "%s,%s,%s,%d,%d,%g,%.4g,%.5f,%.5f,%.5f,%.5f,%.5f\n",
                  r.v.model.c_str(), r.v.mesh.c_str(), r.v.fastsim.c_str(), r.v.n, r.v.n,
                  r.v.tolerance, r.nsPerStep, worstOf(r, scenes, ""), sum / r.errors.size(),
                  worstOf(r, scenes, "freq"), worstOf(r, scenes, "combined"),
                  worstOf(r, scenes, "load"));
    table << line;
    std::cerr << line;
    for (size_t k = 0; k < scenes.size(); ++k) {
      std::snprintf(line, sizeof line, "%s,%s,%s,%d,%d,%g,%s,%s,%.5f,%.4g,%.3f\n",
                    r.v.model.c_str(), r.v.mesh.c_str(), r.v.fastsim.c_str(), r.v.n, r.v.n,
                    r.v.tolerance, scenes[k].scene.name.c_str(), scenes[k].family.c_str(),
                    r.errors[k], r.nsPerScene[k], r.nssShare[k]);
      per << line;
    }
  }
}

void addOptions(CLI::App& app, Options* o) {
  app.description("Cost per step against accuracy for every model and mesh.");
  tools::option(app, "--out", &o->out, "output folder (must exist)");
  tools::option(
      app, "--models", &o->models,
      "NAME[:MESH[:FASTSIM]],...: mesh fixed when left out; a FASTSIM pins one variant of "
      "that entry");
  tools::option(app, "--meshes", &o->meshes, "FastSim meshes N x N");
  tools::option(app, "--exact-meshes", &o->exactMeshes, "grids N x N of the exact model");
  tools::option(app, "--tolerances", &o->tolerances, "auto: one run per tolerance");
  tools::option(app, "--fastsim", &o->fastsims, "the variants every FastSim model runs",
                {"classic", "calibrated"});
  tools::option(app, "--grid", &o->grid,
                "exact reference grid of the harmonic and combined scenes");
  tools::option(app, "--load-grid", &o->loadGrid,
                "exact reference grid of the varying-load scenes");
  tools::option(app, "--periods", &o->periods, "periods of each paper scene");
  tools::option(app, "--repeats", &o->repeats, "timed passes per scene (at least 1)");
  tools::option(app, "--rounds", &o->rounds, "sweeps of every model timed (at least 1)");
  app.add_option("--set", o->sets,
                 "a ContactParameters field for every model run (repeatable; not fastsim)")
      ->allow_extra_args(false)  // one NAME=VALUE a word, commas included; each --set adds one
      ->option_text("NAME=VALUE")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            const size_t eq = v.find('=');
            if (eq == std::string::npos) return "needs NAME=VALUE, got " + v;
            if (v.substr(0, eq) == "fastsim")  // each row names its variant: set it per row
              return "fastsim: use --fastsim or --models NAME:MESH:FASTSIM";
            ContactParameters probe;  // an unknown name fails here, not as a skip of every model
            try {
              setParameter(&probe, v.substr(0, eq), v.substr(eq + 1));
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
            return "";
          },
          "NAME=VALUE"));
  tools::flag(app, "--refresh", &o->refresh, "recompute the cached exact reference");
  tools::option(app, "--parts", &o->parts,
                "all, paper (the elliptic scenes: speed_accuracy.csv) or patches (the real-profile "
                "cases: speed_accuracy_patches.csv)")
      ->check(CLI::IsMember({"all", "paper", "patches"}));
  tools::option(app, "--cases", &o->cases, "A-2.2's wheelset states (a22_cases.csv)");
  tools::option(app, "--patch-grid", &o->patchGrid,
                "real-profile cases: exact reference grid mx (my = 3/4 mx)");
  tools::option(app, "--patch-exact-grids", &o->patchExactGrids,
                "real-profile cases: the exact model's grids mx (my = 3/4 mx)");
  app.callback([o] {
    o->repeats = std::max(1, o->repeats);
    o->rounds = std::max(1, o->rounds);
    for (const std::string& v : o->sets)
      o->overrides.push_back({v.substr(0, v.find('=')), v.substr(v.find('=') + 1)});
  });
}

int run(const Options& o) {
  tools::requireFolder(o.out);
  if (o.parts != "paper") patchPart(o, variants(o));
  if (o.parts == "patches") return 0;
  std::vector<Scene> paper = paperScenes(o);
  if (o.refresh || !readCache(o, &paper)) {
    std::cerr << "computing the exact reference (grid " << o.grid << ", load grid " << o.loadGrid
              << ") into " << cachePath(o) << "\n";
    computeReferences(o, &paper);
    writeCache(o, paper);
  }
  std::vector<Scene> scenes = harmonicScenes(o);
  scenes.insert(scenes.end(), paper.begin(), paper.end());
  std::vector<Result> results;
  for (const Variant& v : variants(o)) {
    try {
      results.push_back(evaluate(o, v, scenes));
    } catch (const std::invalid_argument& e) {  // a model or option this build does not provide
      std::cerr << "skipping " << v.model << ":" << v.mesh << ":" << v.fastsim << " " << v.n << "x"
                << v.n << ": " << e.what() << "\n";
    }
  }
  retime(o, scenes, &results);
  writeResults(o, results, scenes);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("speed_accuracy", argc, argv, addOptions, run);
}
