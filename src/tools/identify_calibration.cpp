// identify_calibration: identifies the calibrated FastSim's flexibility ratios
// (config/calibration.bin, calibration_table.hpp) against our exact half-space solver, and
// writes the steady creep curves exact / classic / calibrated for plots and tests.
// Exact creep curves are cached (--exact, doc/data/steady_exact_curves.csv): a point found there
// is read, not recomputed; missing points are solved and the cache rewritten.
// Curves: along a ray of normalised creepage (e1, e2, e3) (calibration_table.hpp), kinds 11, 22,
// 23 one creepage each; combined rays xe (1, 1, 0), xep (1, 1, 1), opp (1, -1, 1), spin
// (0.3, -0.3, 1) (large spin, opposite signs), h1 (1, 0.5, 0.8), h2 (0.4, 1, -0.7) and the small
// spin shares h3 (1, -1, 0.2), h4 (0.5, 1, 0.25), h5 (1, 0.6, -0.5), h6 (0.8, 0.8, 0.55), h7 (0.6,
// 1, -0.33) and h8 (1, 0.4, 0.3) (7.4 and 7.2 % of e^2, between h4 and the first knot 0.1), and
// r1-r16, spread between the grid's directions: the combined correction's evaluation rays, none
// on its direction grid.
// Identification, per a/b and kind: at each knot epsilon the ratio r minimising FastSim's error
// against the exact point, max(|dFx|, |dFy|) / (mu fz), scanned near the previous knot's ratio.
// Spin: on a flattened bound (shape 23s per a/b), the pair (ratio of L3, ratio of L3x, kind 23x)
// minimising the larger of that and 0.2 |dMz| / peak |Mz| (the 0.01 mu fz and 5 % of the
// peak weighed alike).
// Combined creepages with spin: on a grid of directions (gridRay) and at each knot, multipliers
// of L1, L2, L3, of the bound's shape and of L3x on top of the single kinds' table (kinds c1, c2,
// c3, cs, c3x).
// Eta: its ratio with the lateral coupling (22, 22c) on eta alone; without spin its own ratio,
// coupling and bound shape with eta's drive's slope (22n, 22cn, 22s, 22b) on eta alone and
// xi = eta together.
// Per FastSim mesh (--nx 5,10,20,30,40): FastSim's own discretisation error differs per mesh, the
// exact curves do not, so one cache serves every mesh; each mesh's rows carry its fastsim_nx.
// Each (mesh, a/b) is identified on its own, needing no other's: they run as parallel jobs
// (--threads), each writing only its own result, so the table is the same whatever the number.
// Options: identify_calibration --help.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "core/exact/halfspace_solver.hpp"
#include "core/fastsim/fastsim.hpp"
#include "tool_options.hpp"
#include "validation/steady_curves.hpp"

using namespace wheel_rail_contact;
using namespace wheel_rail_contact::calibration;

namespace {

// A kind's short name in the table (calibration_schema.hpp); `multiplier`: the combined
// correction's multiplier k's.
const char* code(int k, bool multiplier = false) {
  return (multiplier ? kMultiplierInfo[k] : kKindInfo[k]).code.data();
}

const char* const kDefaultExact = "doc/data/steady_exact_curves.csv";

template <std::size_t N>
std::vector<double> gridOf(const double (&values)[N]) {
  return std::vector<double>(values, values + N);
}

struct Options {
  std::string out, exact = kDefaultExact, curves, table, convert;
  int dump = -1;  // --dump: the mesh written as CSV (0: every mesh)
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int grid = 20, nx = 20;  // nx: the mesh being identified or evaluated, one of `meshes`
  std::vector<int> meshes = {20};
  double nu = 0.28, G = 8.2e10, mu = 0.3, fz = 1e4;
  // The grids: the shipped table's (calibration_schema.hpp, where each is explained).
  std::vector<double> ratios = gridOf(calibration::kAOverB), knots = gridOf(calibration::kKnots);
  std::vector<double> points = {0.05, 0.15, 0.3, 0.6, 0.9, 1.25, 1.75, 2.5, 4, 6, 9, 13};
  std::vector<double> corrKnots = gridOf(calibration::kCorrectionKnots),
                      spinShares = gridOf(calibration::kSpinShares),
                      xiShares = gridOf(calibration::kXiShares);
  // The smoothing sweeps' pull towards the neighbouring directions (identifyCorrection), in
  // mu fz per unit ln multiplier; 0: each direction fitted alone.
  double smoothing = 0.01;
  bool solveGrid = false, gridOnly = false, momentStudy = false;
  bool coupling = true;   // eta's lateral coupling (kind 22c) identified and used
  bool etaSlope = true;   // with it, eta's drive's slope (kind 22b)
  bool etaNoSpin = true;  // with both, eta without spin (kinds 22n, 22cn, 22s; 22b refitted)
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Identifies the calibrated FastSim's table against the exact half-space solver and writes "
      "the steady creep curves exact / classic / calibrated.");
  app.footer(
      "Modes: identify_calibration --out FILE [grid options] (identify and write a table);\n"
      "       identify_calibration --dump NX [--table FILE] [--out FILE.csv];\n"
      "       identify_calibration --convert FILE --out FILE.bin;\n"
      "       without --out, --dump or --convert: --table (or the shipped one) is evaluated.");
  tools::option(app, "--out", &o->out,
                "identify and write the table: binary where FILE ends in .bin, with a summary "
                "beside it (FILE less .bin, _summary.txt: the fit errors and the command), else "
                "CSV (else --table, or the shipped one, is evaluated)");
  tools::option(app, "--exact", &o->exact,
                "the exact points' cache, read and extended (the default, relative to the "
                "repository root, must exist; a FILE that does not is a new cache)");
  tools::option(app, "--curves", &o->curves,
                "write exact / classic / calibrated curves at --points for every ray");
  tools::option(app, "--table", &o->table,
                "a table file, binary or CSV (default: the one shipped in the library; classic: "
                "no table)");
  tools::option(app, "--threads", &o->threads,
                "identify that many meshes and a/b at once (default: the CPU's threads); the "
                "table is the same whatever the number");
  tools::option(app, "--dump", &o->dump,
                "write mesh NX of the table (0: every mesh) as CSV, to --out or stdout");
  tools::option(app, "--convert", &o->convert,
                "read a table (CSV or binary) and write it to --out (.bin: binary, else CSV)");
  tools::option(app, "--grid", &o->grid, "exact solver elements per axis");
  tools::option(app, "--nx", &o->meshes,
                "FastSim nodes per axis, one table block per mesh (fastsim_nx); evaluation: each "
                "mesh on the table's, interpolated between its meshes (one --nx with --curves)");
  tools::option(app, "--nu", &o->nu, "Poisson's ratio");
  // The grids' defaults: the shipped table's (src/core/calibration/calibration_schema.hpp).
  tools::option(app, "--ab", &o->ratios, "the table's a/b");
  tools::option(app, "--knots", &o->knots, "the single kinds' knots in e");
  tools::option(app, "--points", &o->points, "the curves' points in e (--curves)");
  tools::option(app, "--correction-knots", &o->corrKnots, "the combined correction's knots in e");
  tools::option(app, "--spin-shares", &o->spinShares,
                "the combined correction's direction grid, spin's shares of e^2 ('': no "
                "correction)",
                {}, true);
  tools::option(app, "--xi-shares", &o->xiShares,
                "the combined correction's direction grid, xi's shares of the rest ('': no "
                "correction)",
                {}, true);
  tools::option(app, "--smoothing", &o->smoothing,
                "the pull of each direction's multipliers towards its neighbours' (mu fz per "
                "unit ln multiplier; 0: each direction fitted alone)");
  app.add_flag_callback(
      "--no-coupling", [o] { o->coupling = false; },
      "no lateral coupling (kind 22c): eta's ratio fitted to the force alone");
  app.add_flag_callback(
      "--no-eta-slope", [o] { o->etaSlope = false; },
      "no slope of eta's drive (kind 22b): uniform along the strip, as classic");
  app.add_flag_callback(
      "--no-eta-without-spin", [o] { o->etaNoSpin = false; },
      "no set of eta's own without spin (kinds 22n, 22cn, 22s): the pair fitted on eta alone "
      "holds at every share of spin, 22b fitted on it");
  tools::flag(app, "--solve-grid", &o->solveGrid,
              "only solve the exact points the table and curves need (a long job; the cache is "
              "saved as it goes)");
  tools::flag(app, "--grid-only", &o->gridOnly,
              "with --solve-grid: the direction grid's points, not the rays'");
  tools::flag(app, "--moment-study", &o->momentStudy,
              "per ray and a/b at --points, FastSim's errors on the table (or --table) and "
              "refitted point by point with and without two terms the core does not have; one "
              "--nx, no table written");
}

struct Ray {
  std::string name;
  double e[3];
};
const Ray kRays[] = {{"11", {1, 0, 0}},
                     {"22", {0, 1, 0}},
                     {"23", {0, 0, 1}},
                     {"xe", {1, 1, 0}},
                     {"xep", {1, 1, 1}},
                     {"opp", {1, -1, 1}},
                     {"spin", {0.3, -0.3, 1}},
                     {"h1", {1, 0.5, 0.8}},
                     {"h2", {0.4, 1, -0.7}},
                     {"h3", {1, -1, 0.2}},
                     {"h4", {0.5, 1, 0.25}},
                     {"h5", {1, 0.6, -0.5}},
                     {"h6", {0.8, 0.8, 0.55}},
                     {"h7", {0.6, 1, -0.33}},
                     {"h8", {1, 0.4, 0.3}},
                     // r1-r12: twelve directions (s3, t, sign of eta phi) spread between the
                     // grid's, held out; r13-r16 probe spin shares 0.55-0.71, mostly eta phi < 0
                     // (doc/calibrated_fastsim.md, "Steady accuracy").
                     {"r1", {0.7629, 0.6229, 0.1732}},
                     {"r2", {0.6066, 0.7430, -0.2828}},
                     {"r3", {0.8798, 0.2933, 0.3742}},
                     {"r4", {0.2811, 0.8432, -0.4583}},
                     {"r5", {0.6541, 0.5121, 0.5568}},
                     {"r6", {0.4552, 0.5940, -0.6633}},
                     {"r7", {0.5548, 0.2687, -0.7874}},
                     {"r8", {0.1643, 0.3912, 0.9055}},
                     {"r9", {0.1581, 0.1581, -0.9747}},
                     {"r10", {0.9424, 0.2586, -0.2121}},
                     {"r11", {0.7736, 0.5307, 0.3464}},
                     {"r12", {0.3098, 0.4733, 0.8246}},
                     {"r13", {0.3000, 0.6000, -0.7416}},
                     {"r14", {0.4806, 0.4347, -0.7616}},
                     {"r15", {0.3735, 0.4129, 0.8307}},
                     {"r16", {0.5109, 0.1703, -0.8426}},
                     // r17-r28: twelve directions drawn at random (s3 uniform in 0.03-0.97, t in
                     // 0-1, signs alternating; Python's random, seed 19) before the grid was made
                     // denser: the held-out set that judges it.
                     {"r17", {0.5116, 0.2678, 0.8164}},
                     {"r18", {0.4959, 0.4846, -0.7206}},
                     {"r19", {0.7734, 0.0437, 0.6324}},
                     {"r20", {0.3217, 0.7710, -0.5495}},
                     {"r21", {0.4344, 0.7320, 0.5248}},
                     {"r22", {0.4212, 0.6963, -0.5811}},
                     {"r23", {0.5318, 0.7655, 0.3622}},
                     {"r24", {0.6211, 0.5403, -0.5678}},
                     {"r25", {0.2350, 0.8516, 0.4685}},
                     {"r26", {0.6503, 0.5973, -0.4695}},
                     {"r27", {0.6660, 0.4015, 0.6287}},
                     {"r28", {0.2986, 0.3549, -0.8859}},
                     // r29-r40: drawn as r17-r28 (seed 29) after the grid and its smoothing were
                     // chosen, and looked at once.
                     {"r29", {0.3966, 0.5454, 0.7384}},
                     {"r30", {0.2253, 0.3537, -0.9078}},
                     {"r31", {0.4106, 0.5672, 0.7139}},
                     {"r32", {0.7512, 0.1231, -0.6485}},
                     {"r33", {0.6229, 0.6961, 0.3571}},
                     {"r34", {0.5150, 0.7025, -0.4912}},
                     {"r35", {0.1013, 0.1446, 0.9843}},
                     {"r36", {0.4090, 0.4810, -0.7754}},
                     {"r37", {0.3560, 0.3958, 0.8465}},
                     {"r38", {0.5928, 0.6771, -0.4361}},
                     {"r39", {0.6818, 0.3486, 0.6431}},
                     {"r40", {0.2944, 0.5954, -0.7476}},
                     // r41-r46: drawn as r17-r28 but with s3 in 0.03-0.1 (seed 41) after spin's
                     // share 0.045 and xi's 0.9375 were chosen, and looked at once (r46 again
                     // when the correction's knots 3.75 and 5.5 were).
                     {"r41", {0.4665, 0.8519, 0.2381}},
                     {"r42", {0.9358, 0.2874, -0.2040}},
                     {"r43", {0.8009, 0.5367, 0.2654}},
                     {"r44", {0.5977, 0.7577, -0.2621}},
                     {"r45", {0.7277, 0.6238, 0.2850}},
                     {"r46", {0.7782, 0.5566, -0.2910}}};

// The direction grid of the combined correction: spin's share s3 = e3^2 / e^2, xi's share of the
// rest t = e1^2 / (e1^2 + e2^2), and the relative sign of eta and phi (xi's sign only mirrors).
Ray gridRay(double s3, double t, int sign) {
  char name[48];
  std::snprintf(name, sizeof name, "g%g_%g%c", s3, t, sign > 0 ? '+' : '-');
  return {name,
          {std::sqrt((1.0 - s3) * t), std::sqrt((1.0 - s3) * (1.0 - t)), sign * std::sqrt(s3)}};
}

std::vector<Ray> gridRays(const Options& o) {
  std::vector<Ray> rays;
  for (double s3 : o.spinShares)
    for (double t : o.xiShares)
      for (int sign : {1, -1})
        if (sign > 0 || t < 1.0) rays.push_back(gridRay(s3, t, sign));
  return rays;
}

// Normalised forces: fx, fy over mu fz, mz over mu fz sqrt(ab).
struct Point {
  double fx = 0.0, fy = 0.0, mz = 0.0;
};

// The patch of a/b = g at the tool's load: sqrt(ab) = 5 mm (the curves are scale free).
struct Setup {
  double a, b, G, nu, mu, fz;
  CreepCoefficients k;
  Setup(const Options& o, double g)
      : a(5e-3 * std::sqrt(g)),
        b(5e-3 / std::sqrt(g)),
        G(o.G),
        nu(o.nu),
        mu(o.mu),
        fz(o.fz),
        k(kalkerCoefficients(g, o.nu)) {}
  // The creepages at normalised creepage e along ray r (|e_ray| scaled to e).
  Creepages creepages(const Ray& r, double e) const {
    const double n = std::sqrt(r.e[0] * r.e[0] + r.e[1] * r.e[1] + r.e[2] * r.e[2]);
    const double s = e / n * mu * fz / (G * a * b);
    return {s * r.e[0] / k.c11, s * r.e[1] / k.c22, s * r.e[2] / (k.c23 * std::sqrt(a * b))};
  }
  Point normalised(double fx, double fy, double mz) const {
    const double m = mu * fz;
    return {fx / m, fy / m, mz / (m * std::sqrt(a * b))};
  }
};

using Key = std::tuple<double, std::string, double>;  // a/b, ray, epsilon
struct Solved {
  Point p;
  Creepages c;
};

class ExactCache {
 public:
  // The points are keyed by a/b, ray and e alone: a cache made for another setup (nu, grid, G,
  // mu, fz; its first line) is refused rather than read as this one's.
  ExactCache(const std::string& path, const Options& o) : path_(path), o_(o) {
    std::ifstream in(path);
    std::string first;
    if (in && std::getline(in, first) && first != setupLine())
      throw std::runtime_error("--exact " + path + " was solved for another setup:\n  " + first +
                               "\nnot\n  " + setupLine() +
                               "\n(--nu, --grid: give each setup a cache of its own)");
    for (const SteadyCurvePoint& p : readSteadyCurves(path))
      map_[Key{p.aOverB, p.ray, p.epsilon}] = {{p.fx, p.fy, p.mz}, p.c};
  }
  // Thread-safe: the parallel jobs share the cache (a point missing is solved under the lock).
  Point at(double g, const Ray& r, double e) {
    std::lock_guard<std::mutex> lock(mutex_);
    const Key key{g, r.name, e};
    auto it = map_.find(key);
    if (it != map_.end()) return it->second.p;
    const Setup s(o_, g);
    Point p;
    if (e > 0.0) {
      if (!solver_ || solverAB_ != g) {  // one influence kernel per a/b
        solver_ = std::make_unique<HalfspaceSolver>(
            HalfspaceGrid::covering(s.a, s.b, o_.grid, o_.grid), s.G, s.nu);
        solver_->setHertzPressure(s.a, s.b, s.fz);
        solverAB_ = g;
      }
      const HalfspaceSolution& x = solver_->solve(RollingMode::kSteady, s.creepages(r, e), s.mu);
      if (!x.converged)
        std::cerr << "warning: exact not converged at " << g << " " << r.name << " " << e << "\n";
      p = s.normalised(x.fx, x.fy, x.mz);
    }
    map_[key] = {p, s.creepages(r, e)};
    dirty_ = true;
    ++solved_;
    return p;
  }
  int solved() const { return solved_; }
  // The cache's first line: the setup its points were solved for.
  std::string setupLine() const {
    std::ostringstream s;
    s << "# Exact steady creep curves (our half-space solver, " << o_.grid << "x" << o_.grid
      << " elements over 1.1a x 1.1b, Hertz pressure; G " << o_.G << " Pa, nu " << o_.nu << ", mu "
      << o_.mu << ", fz " << o_.fz << " N, sqrt(ab) 5 mm)";
    return s.str();
  }
  void save() {
    if (!dirty_) return;
    dirty_ = false;
    std::ofstream out = tools::writeFile(path_);
    out << setupLine() << "\n"
        << "# made by: identify_calibration (src/tools/identify_calibration.cpp); a cache: its "
           "points are "
           "read, not recomputed\n"
        << "# epsilon: normalised creepage (calibration_table.hpp); fx, fy over mu fz; mz over "
           "mu fz sqrt(ab)\n"
        << kSteadyCurvesHeader << "\n";
    char line[256];
    for (const auto& [key, v] : map_) {
      const Creepages& c = v.c;
      const Point& p = v.p;
      std::snprintf(line, sizeof line, "%g,%s,%g,%.6g,%.6g,%.6g,%.6f,%.6f,%.6f\n", std::get<0>(key),
                    std::get<1>(key).c_str(), std::get<2>(key), c.xi, c.eta, c.phi, p.fx, p.fy,
                    p.mz);
      out << line;
    }
  }

 private:
  std::string path_;
  Options o_;
  std::map<Key, Solved> map_;
  bool dirty_ = false;
  int solved_ = 0;
  std::unique_ptr<HalfspaceSolver> solver_;
  double solverAB_ = 0.0;
  std::mutex mutex_;
};

// A FastSim evaluation's mesh and traction field, one per thread, kept from one evaluation to the
// next: the identifier runs FastSim millions of times on a handful of patches, and a mesh built
// for each run cost a third of the time (40x40). Kept, they give the same results bit for bit:
// the mesh is a function of (nx, a, b) alone, the march writes every value of the field it reads
// but the bound, and the bound is a function of (fz, mu, shape) on the mesh: written again only
// where one of them changed (a search moving L1, L2 or L3 keeps the shape).
struct Scratch {
  int nx = 0;
  double a = 0.0, b = 0.0;
  PatchMesh mesh;
  TractionField f;
  double fz = 0.0, mu = 0.0, shape = std::numeric_limits<double>::quiet_NaN();  // f's bound's
  // The bound of (fz, mu, shape) into f (flattenedBound).
  void bound(double boundFz, double boundMu, double boundShape) {
    if (boundFz == fz && boundMu == mu && boundShape == shape) return;
    flattenedBound(mesh, a, b, boundFz, boundMu, boundShape, &f);
    fz = boundFz;
    mu = boundMu;
    shape = boundShape;
  }
};
Scratch& scratch(int nx, double a, double b) {
  thread_local Scratch s;
  if (s.nx != nx || s.a != a || s.b != b) {
    s = Scratch();
    s.mesh = PatchMesh(nx, nx, a, b);
    s.f.resize(s.mesh.size());
    s.nx = nx;
    s.a = a;
    s.b = b;
  }
  return s;
}

// The combined correction's multipliers at a knot, in PatchCalibration::correction's order:
// of L1, L2, L3, of the bound's shape, and of L3x besides L3's; the table's kinds for them.
using calibration::kMultipliers;
using Multipliers = std::array<double, kMultipliers>;
constexpr Multipliers kNoCorrection = {1.0, 1.0, 1.0, 1.0, 1.0};
Multipliers expOf(const double* l) {
  Multipliers m;
  for (int p = 0; p < kMultipliers; ++p) m[p] = std::exp(l[p]);
  return m;
}

// Steady FastSim at a/b = g along ray r at e on the table's flexibilities (`base`, without a
// combined correction) with L1, L2, L3 (L3x with L3) multiplied by m[0..2], the bound's shape by
// m[3] and L3x by m[4] besides (PatchCalibration::correction's order).
Point fastsimCorrected(const Options& o, double g, const Ray& r, double e,
                       const PatchCalibration& base, const double* m,
                       bool hertzShapeBlend = false) {
  const Setup s(o, g);
  Scratch& scratchField = scratch(o.nx, s.a, s.b);
  const Creepages c = s.creepages(r, e);
  const CalibratedStep step = base.step(s.a, s.b, s.G, s.k, s.mu * s.fz, c);
  double shape = std::min(calibration::kMaxBoundShape, step.boundShape * m[3]);
  if (hertzShapeBlend)  // as the table with its correction does (towardsFullSlip)
    shape = PatchCalibration::hertzShapeBlend(
        shape, e, r.e[2] * r.e[2] / (r.e[0] * r.e[0] + r.e[1] * r.e[1] + r.e[2] * r.e[2]), g);
  scratchField.bound(s.fz, s.mu, shape);
  Flexibilities L = step.L;
  L.L3x = L.spinX() * m[2] * m[4];
  L.L1 *= m[0];
  L.L2 *= m[1];
  L.L3 *= m[2];
  const CreepForces y = steadyFastSim(scratchField.mesh, L, c, &scratchField.f);
  return s.normalised(y.fx, y.fy, y.mz);
}

// Steady FastSim at a/b = g along ray r at e, flexibilities (and bound) as the table `cal` makes
// them.
Point fastsimAt(const Options& o, double g, const Ray& r, double e, const PatchCalibration& cal) {
  return fastsimCorrected(o, g, r, e, cal, kNoCorrection.data());
}

// FastSim along pure kind `kind` with L_kind scaled by ratio (spin: its longitudinal drive's
// flexibility L3x by ratioX besides), with the lateral coupling `couple` (kind 22c).
Point fastsimScaled(const Options& o, double g, int kind, double e, double ratio,
                    double ratioX = 1.0, double shape = 0.0, double couple = 0.0) {
  const Setup s(o, g);
  Scratch& scratchField = scratch(o.nx, s.a, s.b);
  const PatchMesh& mesh = scratchField.mesh;
  TractionField& f = scratchField.f;
  scratchField.bound(s.fz, s.mu, shape);
  const Creepages c = s.creepages(kRays[kind], e);
  Flexibilities L = kalkerFlexibilities(s.a, s.b, s.G, s.k);
  (kind == 0 ? L.L1 : kind == 1 ? L.L2 : L.L3) *= ratio;
  if (kind == 2) L.L3x = L.L3 * ratioX;
  L.lateralCoupling = PatchCalibration::lateralCoupling(couple, s.a, s.b, s.k);
  const CreepForces x = steadyFastSim(mesh, L, c, &f);
  return s.normalised(x.fx, x.fy, x.mz);
}

// The exact curve's peak |Mz| along ray r over the normalised creepages `at` (e = 0, no moment,
// is not looked up: it need not be in the cache).
double peakMoment(ExactCache* exact, double g, const Ray& r, const std::vector<double>& at) {
  double peak = 0.0;
  for (double e : at)
    if (e > 0.0) peak = std::max(peak, std::abs(exact->at(g, r, e).mz));
  return peak;
}

double pointError(const Point& p, const Point& x, double mzPeak) {
  const double f = std::max(std::abs(p.fx - x.fx), std::abs(p.fy - x.fy));
  return mzPeak > 0.0 ? f + 0.2 * std::abs(p.mz - x.mz) / mzPeak : f;
}

// Spin with its two parameters: the larger of the force error and the moment's (0.01 mu fz and 5 %
// of the peak weighed alike), so that neither is traded away for the other.
double spinError(const Point& p, const Point& x, double mzPeak) {
  return std::max(std::max(std::abs(p.fx - x.fx), std::abs(p.fy - x.fy)),
                  0.2 * std::abs(p.mz - x.mz) / mzPeak);
}

// The pull of the lateral coupling towards the previous knot's, in mu fz per unit of c: the fit
// along eta's curve has near-equal optima of c and L2's ratio where the curve saturates.
constexpr double kCouplingPull = 2e-3;
// Eta's drive's slope (kind 22b): its range, the window around the previous knot's, and the pull
// (mu fz per unit) towards 0 and the previous knot's.
constexpr double kEtaSlopeMax = 2.0, kEtaSlopeStep = 0.5, kEtaSlopePull = 2e-3;

// Eta alone with the coupling: spinError, and the force error held below kLateralForceCap (a
// steep penalty above it). Where Fy and Mz cannot both be fitted (a/b 5, from e = 0.35 to 1.25),
// the plain error traded the force (0.013 mu fz, over the single-creepage target 0.01) for the
// moment; there the moment yields now.
constexpr double kLateralForceCap = 0.0075;
double lateralError(const Point& p, const Point& x, double mzPeak) {
  const double f = std::max(std::abs(p.fx - x.fx), std::abs(p.fy - x.fy));
  return std::max(f, 0.2 * std::abs(p.mz - x.mz) / mzPeak) +
         100.0 * std::max(0.0, f - kLateralForceCap);
}

// A search over two parameters: the point and its cost, the best found so far.
struct PairSearch {
  double x0, x1, cost;
};

// The (n + 1)^2 grid over [lo0, hi0] x [lo1, hi1]: a point of lower cost replaces `best`.
template <class Cost>
void scanPair(const Cost& cost, double lo0, double hi0, double lo1, double hi1, int n,
              PairSearch* best) {
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double x0 = lo0 + (hi0 - lo0) * i / n, x1 = lo1 + (hi1 - lo1) * k / n;
      const double c = cost(x0, x1);
      if (c < best->cost) *best = {x0, x1, c};
    }
}

// Pattern refinement from `best` along both axes and diagonals, steps of h halving down to 1e-5.
template <class Cost>
void refinePair(const Cost& cost, double h, PairSearch* best) {
  for (; h > 1e-5; h *= 0.5)
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& [d0, d1] : {std::pair<double, double>{h, 0},
                                   {-h, 0},
                                   {0, h},
                                   {0, -h},
                                   {h, h},
                                   {-h, -h},
                                   {h, -h},
                                   {-h, h}}) {
        const double c = cost(best->x0 + d0, best->x1 + d1);
        if (c < best->cost) *best = {best->x0 + d0, best->x1 + d1, c}, moved = true;
      }
    }
}

// A minimum of cost over [lo, hi]: the best of `start` (a point and its cost) and n + 1 points
// evenly spaced, then `iterations` golden-section steps within a grid step either side of it (kept
// inside [lo, hi] where `clamp`); the section's midpoint where it does better.
template <class Cost>
double scanThenRefine(const Cost& cost, double lo, double hi, int n, int iterations,
                      std::pair<double, double> start, bool clamp) {
  auto [best, bestCost] = start;
  for (int i = 0; i <= n; ++i) {
    const double x = lo + (hi - lo) * i / n, c = cost(x);
    if (c < bestCost) bestCost = c, best = x;
  }
  double a = best - (hi - lo) / n, b = best + (hi - lo) / n;
  if (clamp) a = std::max(lo, a), b = std::min(hi, b);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < iterations; ++it) {
    const double c1 = b - phi * (b - a), c2 = a + phi * (b - a);
    if (cost(c1) < cost(c2))
      b = c2;
    else
      a = c1;
  }
  return cost(0.5 * (a + b)) < bestCost ? 0.5 * (a + b) : best;
}

struct KindFit {
  std::vector<double> ratio, ratioX, error;
  std::vector<double> couple;  // eta: the lateral coupling (22c), per knot
  double shape = 0.0;          // spin: the bound's shape
};

// Eta alone with the lateral coupling (kind 22c): at each knot the pair (ln ratio of L2, coupling
// c) that fits Fy and Mz together (spinError), by a grid near the previous knot's pair (one
// continuous branch) and pattern refinement, with a small pull of the ratio towards 1 and of c
// towards the previous knot's: of near-equal optima the one that continues the curve. Knot 0 takes
// the first fitted knot's coupling (linear theory's moment: the coupling's only work there).
KindFit identifyLateral(const Options& o, ExactCache* exact, double g) {
  const double mzPeak = peakMoment(exact, g, kRays[1], o.knots);
  KindFit fit;
  double lr = 0.0, couple = 0.0;
  bool first = true;
  for (double e : o.knots) {
    if (e == 0.0) {
      fit.ratio.push_back(1.0);
      fit.couple.push_back(0.0);  // set below
      fit.error.push_back(0.0);
      continue;
    }
    const Point x = exact->at(g, kRays[1], e);
    const double previous = couple;
    auto cost = [&](double l, double c) {
      return lateralError(fastsimScaled(o, g, 1, e, std::exp(l), 1.0, 0.0, c), x, mzPeak) +
             1e-3 * std::abs(l) + (first ? 0.0 : kCouplingPull * std::abs(c - previous));
    };
    PairSearch best{lr, couple, cost(lr, couple)};
    if (first)
      scanPair(cost, -0.6, 0.6, -2.0, 1.0, 40, &best);
    else
      scanPair(cost, lr - 0.4, lr + 0.4, couple - 0.4, couple + 0.4, 40, &best);
    refinePair(cost, 0.02, &best);
    lr = best.x0;
    couple = best.x1;
    first = false;
    fit.ratio.push_back(std::exp(lr));
    fit.couple.push_back(couple);
    fit.error.push_back(
        lateralError(fastsimScaled(o, g, 1, e, std::exp(lr), 1.0, 0.0, couple), x, mzPeak));
  }
  if (fit.couple.size() > 1) fit.couple[0] = fit.couple[1];
  fit.ratioX.assign(fit.ratio.size(), 1.0);
  return fit;
}

// Xi beside eta (ray xe): the slope beta of eta's drive (kind 22b) at each knot, on the single
// kinds' table `cal` (11, 22 and 22c fitted): a scan near the previous knot's beta (one continuous
// branch) and golden-section refinement, against Fx, Fy and Mz together (spinError's norm), pulled
// towards 0 and the previous knot's. Knot 0 is 0: linear theory's
// moment of xi with eta is the coupling's already. `error` gets each knot's fit error.
std::vector<double> identifyEtaSlope(const Options& o, ExactCache* exact, double g,
                                     const PatchCalibration& cal, std::vector<double>* error) {
  const Ray& xe = kRays[3];
  const double mzPeak = peakMoment(exact, g, xe, o.knots);
  std::vector<double> beta;
  error->clear();
  double previous = 0.0;
  for (double e : o.knots) {
    if (e == 0.0) {
      beta.push_back(0.0);
      error->push_back(0.0);
      continue;
    }
    const Point x = exact->at(g, xe, e);
    const Setup s(o, g);
    Scratch& scratchField = scratch(o.nx, s.a, s.b);
    const PatchMesh& mesh = scratchField.mesh;
    TractionField& f = scratchField.f;
    const Creepages c = s.creepages(xe, e);
    const CalibratedStep step = cal.step(s.a, s.b, s.G, s.k, s.mu * s.fz, c);
    scratchField.bound(s.fz, s.mu, step.boundShape);
    auto fit = [&](double b) {
      Flexibilities L = step.L;
      PatchCalibration::setEtaSlope(b, s.a, &L);
      const CreepForces y = steadyFastSim(mesh, L, c, &f);
      return spinError(s.normalised(y.fx, y.fy, y.mz), x, mzPeak);
    };
    auto cost = [&](double b) {
      return fit(b) + kEtaSlopePull * (std::abs(b) + std::abs(b - previous));
    };
    const double lo = std::max(-kEtaSlopeMax, previous - kEtaSlopeStep),
                 hi = std::min(kEtaSlopeMax, previous + kEtaSlopeStep);
    const double best = scanThenRefine(cost, lo, hi, 50, 30, {previous, cost(previous)}, true);
    previous = best;
    beta.push_back(best);
    error->push_back(fit(best));
  }
  return beta;
}

// Spin's pair (ratio of L3, ratio of L3x) at knot e: a grid over both logarithms near the previous
// knot's pair (one continuous branch), then pattern refinement on halving steps.
// A small pull towards 1 as for the single ratio.
std::pair<double, double> identifySpinPair(const Options& o, double g, double e, const Point& x,
                                           double mzPeak, double previous, double previousX,
                                           double shape, double couple) {
  auto cost = [&](double lr, double lrx) {
    return spinError(fastsimScaled(o, g, 2, e, std::exp(lr), std::exp(lrx), shape, couple), x,
                     mzPeak) +
           1e-3 * (std::abs(lr) + std::abs(lrx));
  };
  // The longitudinal spin drive moves further from knot to knot across the curve's peak (and at
  // a/b = 5 already in the linear range): its window is twice as wide.
  const double c0 = std::log(previous), cx0 = std::log(previousX), span = 0.6, spanX = 1.2;
  PairSearch best{c0, cx0, cost(c0, cx0)};
  scanPair(cost, c0 - span, c0 + span, cx0 - spanX, cx0 + spanX, 48, &best);
  // Where no pair near the previous one fits (FastSim's spin curve past its peak where the exact
  // one is not yet), the whole plausible range: continuity yields to the fit.
  if (best.cost > 0.005)
    scanPair(cost, std::log(0.2), std::log(5.0), std::log(0.1), std::log(10.0), 48, &best);
  refinePair(cost, 2.0 * span / 48, &best);
  return {std::exp(best.x0), std::exp(best.x1)};
}

// Kind `kind` alone (spin: on the lateral coupling `couple` per knot, empty: none).
KindFit identifyKind(const Options& o, ExactCache* exact, double g, int kind, double shape = 0.0,
                     const std::vector<double>& couple = {}) {
  const double mzPeak = kind == 2 ? peakMoment(exact, g, kRays[2], o.knots) : 0.0;
  KindFit fit;
  fit.shape = shape;
  double previous = 1.0, previousX = 1.0;
  for (std::size_t knot = 0; knot < o.knots.size(); ++knot) {
    const double e = o.knots[knot], knotCouple = couple.empty() ? 0.0 : couple[knot];
    if (e == 0.0) {
      fit.ratio.push_back(1.0);
      fit.ratioX.push_back(1.0);
      fit.error.push_back(0.0);
      continue;
    }
    const Point x = exact->at(g, kRays[kind], e);
    if (kind == 2) {
      std::tie(previous, previousX) =
          identifySpinPair(o, g, e, x, mzPeak, previous, previousX, shape, knotCouple);
      fit.ratio.push_back(previous);
      fit.ratioX.push_back(previousX);
      fit.error.push_back(
          spinError(fastsimScaled(o, g, 2, e, previous, previousX, shape, knotCouple), x, mzPeak));
      continue;
    }
    // Scan ln r, then refine around the best by golden section. A small pull towards r = 1 picks
    // the ratio nearest Kalker's where many fit alike (in full slip every large enough ratio
    // saturates a single creepage; a combined step weighs the kinds' ratios, so they must not
    // wander there).
    auto cost = [&](double lr) {
      return pointError(fastsimScaled(o, g, kind, e, std::exp(lr)), x, mzPeak) +
             1e-3 * std::abs(lr);
    };
    // Within a factor e^0.6 of the previous knot's ratio: one continuous curve, no jump to the
    // other branch of a creep curve that rises and falls (spin).
    const double lo = std::max(std::log(0.05), std::log(previous) - 0.6),
                 hi = std::min(std::log(50.0), std::log(previous) + 0.6);
    const double lr = scanThenRefine(cost, lo, hi, 400, 40, {0.0, 1e300}, false);
    previous = std::exp(lr);
    fit.ratio.push_back(previous);
    fit.ratioX.push_back(1.0);
    fit.error.push_back(pointError(fastsimScaled(o, g, kind, e, previous), x, mzPeak));
  }
  // 23x at knot 0 is linear theory's spin moment (C33), which FastSim's L3 = L3x misses; the first
  // knot's fit is in the linear range (the ratio is flat there), and the core applies knot 0's
  // value at every share of spin (PatchCalibration::step).
  if (kind == 2 && fit.ratioX.size() > 1) fit.ratioX[0] = fit.ratioX[1];
  return fit;
}

// Spin: the bound's shape per a/b, the flattest of 1, 0.75, 0.5, 0.25 whose fit keeps every
// knot within the targets (error below 0.01: force 0.01 mu fz, moment 5 % of the peak), else the
// best of them.
KindFit identifySpin(const Options& o, ExactCache* exact, double g,
                     const std::vector<double>& couple) {
  KindFit best;
  double bestWorst = 1e300;
  for (double shape : {1.0, 0.75, 0.5, 0.25}) {
    KindFit fit = identifyKind(o, exact, g, 2, shape, couple);
    const double worst = *std::max_element(fit.error.begin(), fit.error.end());
    if (worst < bestWorst) bestWorst = worst, best = fit;
    if (worst < 0.01) return fit;
  }
  return best;
}

struct CorrectionFit {
  std::vector<Multipliers> m;
  std::vector<double> error;
};

// Jacobi sweeps of the combined correction's smoothing (identifyCorrection).
constexpr int kSmoothingSweeps = 3;
// Normalised creepage up to which the combined correction is 1.
constexpr double kLinearEnd = 0.1;
// Below calibration::kSmallSpinShare a spin-share knot is fitted from this normalised
// creepage on (with towardsFullSlip's blend in the fit, as the table applies it there), below it
// holding the correction interpolated between no spin and the first knot from kSmallSpinShare on:
// kRoundSmallShareFitFrom on a round patch (a/b 1), kSmallShareFitFrom from a/b 2 (or 1/2) on,
// linear in |ln(a/b)| between. On the round patch the knot's own fit below 0.75 made the paper's
// combined2 (spin shares down to 0.01 at e <= 0.61) worse, where the interpolation did not miss;
// on wide and long patches the interpolation left the small shares' partial-slip moment FastSim's
// own, 6-7 % of the peak off at e = 0.3-0.6 (h7, r2 at a/b 0.2, h4 at a/b 2).
constexpr double kRoundSmallShareFitFrom = 0.75, kSmallShareFitFrom = 0.35;
double smallShareFitFrom(double g) {
  const double roundness = std::max(0.0, 1.0 - std::abs(std::log(g)) / std::log(2.0));
  return kSmallShareFitFrom + (kRoundSmallShareFitFrom - kSmallShareFitFrom) * roundness;
}

// The fifth multiplier (of L3x alone, kind c3x) is 1 below this normalised creepage and pulled
// towards 1 harder than the others above it. Fitted freely, it moved the first spin share's fit in
// partial slip, which the small shares hold there (their moment then missed), and wandered in full
// slip along a ridge of near-equal optima; where it is needed (xi-dominant directions with some
// 40 % spin on long patches) it acts from partial slip's end on (doc/calibrated_fastsim.md, "What
// it is", item 5).
constexpr double kSpinDriveFitFrom = 0.75;
constexpr double kSpinDrivePull = 1e-2;

// The multipliers a knot at e searches: the first four, and L3x's from kSpinDriveFitFrom on (its ln
// multiplier, lm[4], is set to 0 below it).
int searchedMultipliers(double e, double* lm) {
  if (e >= kSpinDriveFitFrom) return kMultipliers;
  lm[4] = 0.0;
  return kMultipliers - 1;
}

// Pattern search along the coordinates: from x, steps of +-h along each of its `dims` coordinates
// while they lower `cost`, h halving from 0.2 down to 1e-3, at most `maxSweeps` sweeps per h; a
// point `allowed` rejects is not costed. x ends at the best point found. A point's coordinates
// past `dims` are 0, as every caller holds them (they were left unset, and the fit then hung on
// whatever the stack held there).
constexpr int kMaxSearchDims = 5;
template <class Cost, class Allowed>
void coordinateSearch(double* x, int dims, const Cost& cost, const Allowed& allowed,
                      int maxSweeps) {
  double best = cost(x);
  // The points costed so far, by their bits: a step back to where the search came from (some 15 %
  // of the points) is looked up, not costed again (the same cost: it is a function of the point).
  using Bits = std::array<std::uint64_t, kMaxSearchDims>;
  std::map<Bits, double> costed;
  auto bitsOf = [dims](const double* p) {
    Bits b{};
    std::memcpy(b.data(), p, sizeof(double) * dims);
    return b;
  };
  costed[bitsOf(x)] = best;
  for (double h = 0.2; h > 1e-3; h *= 0.5)
    for (int sweeps = 0, moved = 1; moved && sweeps < maxSweeps; ++sweeps) {
      moved = 0;
      for (int d = 0; d < dims; ++d)
        for (double step : {h, -h}) {
          double t[kMaxSearchDims] = {};
          std::copy(x, x + dims, t);
          t[d] += step;
          if (!allowed(t)) continue;
          const auto [at, fresh] = costed.try_emplace(bitsOf(t), 0.0);
          if (fresh) at->second = cost(t);
          const double c = at->second;
          if (c < best) best = c, std::copy(t, t + dims, x), moved = 1;
        }
    }
}

// Eta without spin (kinds 22n, 22cn, 22s, with 22b): at each knot e, ln ratio of L2, coupling c,
// eta's bound shape and the slope beta fitted together against eta alone's error (lateralError)
// and xi = eta's (spinError), their sum plus the larger (the larger alone gave eta's own moment
// away for xi = eta's on wide patches, where xi = eta had little to gain, and more so at other
// nu), both through the core's step on a table of this knot and the previous one beside the
// single kinds' `cal` (11, 22, 22c, 22b fitted), at the knot and at the cached points since the
// previous knot (fitted at the knots alone, the curves overshot between them). Coordinate search
// from the pair's own (22, 22c, shape 0, 22b) and from the previous knot's four, pulled towards the
// pair's (kEtaNoSpinPairPull) and the previous knot's (one continuous branch: unpulled, the search
// left it where the curves saturate).
// Knot 0: ratio 1, beta 0, and the first knot's coupling and shape (linear theory's moment is the
// coupling's; the bound does not act there).
struct EtaNoSpinFit {
  std::vector<double> ratio, couple, shape, beta, error;
};
constexpr double kEtaNoSpinPull = 2e-3;
// The pull towards the pair's own (22, 22c, shape 0, 22b), in the cost's units per unit: the set
// leaves the pair only where the steady curves gain by it. Pulled by continuity alone it wandered
// from the pair through the end of partial slip on the round patch, where the steady curves gained
// little and nss marched the paper's combined3 (eta's large swings) worse than classic. At 0.02
// the set stayed the pair for eta alone on 10x10 at a/b 5, whose moment then missed by 7 %.
constexpr double kEtaNoSpinPairPull = 0.015;
// xi = eta's error held below this (a steep penalty above it, as kLateralForceCap for eta alone):
// the sum traded xi = eta's moment at a knot on the wide patch (a/b 0.2) past the 5 % of
// the peak for eta's own.
constexpr double kXiEtaCap = 0.009;
EtaNoSpinFit identifyEtaWithoutSpin(const Options& o, ExactCache* exact, double g,
                                    const PatchCalibration& cal) {
  const Ray &eta = kRays[1], &xe = kRays[3];
  const double peakEta = peakMoment(exact, g, eta, o.knots),
               peakXe = peakMoment(exact, g, xe, o.knots);
  EtaNoSpinFit fit;
  double previous[4] = {0.0, 0.0, 0.0, 0.0};  // ln ratio, c, shape, beta
  double ePrevious = 0.0;                     // 0: the first knot after 0 (no previous knot's four)
  for (double e : o.knots) {
    if (e == 0.0) {
      for (auto* v : {&fit.ratio, &fit.couple, &fit.shape, &fit.beta, &fit.error})
        v->push_back(0.0);
      fit.ratio.back() = 1.0;
      continue;
    }
    const bool first = ePrevious == 0.0;
    // Where the fit is costed: the knot, and the cached points since the previous knot (the
    // table is interpolated there between the previous knot's four and these).
    std::vector<double> at = {e};
    if (!first)
      for (double p : o.points)
        if (p > ePrevious && p < e) at.push_back(p);
    std::vector<Point> xEta, xXe;
    for (double p : at) xEta.push_back(exact->at(g, eta, p)), xXe.push_back(exact->at(g, xe, p));
    // The single kinds at the knots 0, the previous knot's e (but on the first) and e, and the
    // candidate as the no-spin kinds and 22b.
    std::string fixed = "a_over_b,kind,epsilon,ratio\n";
    auto row = [&](std::string* t, const char* kind, double knot, double value) {
      char line[128];
      std::snprintf(line, sizeof line, "%.17g,%s,%.17g,%.17g\n", g, kind, knot, value);
      *t += line;
    };
    std::vector<double> knots = {0.0};
    if (!first) knots.push_back(ePrevious);
    knots.push_back(e);
    for (double k : knots) {
      row(&fixed, code(kXiRatio), k, cal.ratio(kXiRatio, k));
      row(&fixed, code(kEtaRatio), k, cal.ratio(kEtaRatio, k));
      row(&fixed, code(kSpinRatio), k, 1.0);
      row(&fixed, code(kEtaCoupling), k, cal.coupling(k));
    }
    // The larger of eta alone's error and xi = eta's over the knot's cell, and the fit's cost: at
    // each place their sum and the larger.
    auto errors = [&](const double* v, double* larger = nullptr) {
      std::string t = fixed;
      for (double k : knots) {
        const bool here = k == e, before = k > 0.0 && !here;
        const double* w = here ? v : before ? previous : nullptr;
        row(&t, code(kEtaDriveSlope), k, w ? w[3] : 0.0);
        row(&t, code(kEtaRatioNoSpin), k, w ? std::exp(w[0]) : 1.0);
        row(&t, code(kEtaCouplingNoSpin), k, w ? w[1] : 0.0);
        row(&t, code(kEtaBoundShapeNoSpin), k, w ? w[2] : 0.0);
      }
      std::istringstream text(t);
      const PatchCalibration one = CalibrationTable::parse(text, "(knot cell)").at(g);
      double sum = 0.0, worst = 0.0;
      for (std::size_t i = 0; i < at.size(); ++i) {
        const double alone = lateralError(fastsimAt(o, g, eta, at[i], one), xEta[i], peakEta),
                     withXi = spinError(fastsimAt(o, g, xe, at[i], one), xXe[i], peakXe);
        sum += std::max(alone, withXi) + alone + withXi + 100.0 * std::max(0.0, withXi - kXiEtaCap);
        worst = std::max(worst, std::max(alone, withXi));
      }
      if (larger) *larger = worst;
      return sum;
    };
    const double pair[4] = {std::log(cal.ratio(kEtaRatio, e)), cal.coupling(e), 0.0,
                            cal.etaSlope(e)};
    auto cost = [&](const double* v) {
      double pull = 0.0;
      if (!first)
        for (int i = 0; i < 4; ++i) pull += std::abs(v[i] - previous[i]);
      double toPair = 0.0;
      for (int i = 0; i < 4; ++i) toPair += std::abs(v[i] - pair[i]);
      return errors(v) + kEtaNoSpinPull * pull + kEtaNoSpinPairPull * toPair;
    };
    auto allowed = [](const double* v) {
      return v[0] > std::log(0.05) && v[0] < std::log(50.0) && v[2] >= calibration::kMinEtaShape &&
             v[2] <= calibration::kMaxBoundShape && std::abs(v[3]) <= kEtaSlopeMax;
    };
    double best[4] = {pair[0], pair[1], pair[2], pair[3]};
    coordinateSearch(best, 4, cost, allowed, 20);
    if (!first) {
      double fromPrevious[4];
      std::copy(previous, previous + 4, fromPrevious);
      coordinateSearch(fromPrevious, 4, cost, allowed, 20);
      if (cost(fromPrevious) < cost(best)) std::copy(fromPrevious, fromPrevious + 4, best);
    }
    double larger;
    errors(best, &larger);
    fit.error.push_back(larger);
    std::copy(best, best + 4, previous);
    ePrevious = e;
    fit.ratio.push_back(std::exp(best[0]));
    fit.couple.push_back(best[1]);
    fit.shape.push_back(best[2]);
    fit.beta.push_back(best[3]);
  }
  if (fit.couple.size() > 1) fit.couple[0] = fit.couple[1], fit.shape[0] = fit.shape[1];
  return fit;
}

// The combined correction's search cost at a knot: a smooth norm of the errors spinError takes the
// larger of (a coordinate search stalls on the ridges of a maximum), with a small pull of the ln
// multipliers `l` towards 1 (kSpinDrivePull on L3x's).
double knotCost(const Point& p, const Point& x, double mzPeak, const double* l) {
  const double dx = p.fx - x.fx, dy = p.fy - x.fy, dm = 0.2 * (p.mz - x.mz) / mzPeak;
  double pull = 0.0;
  for (int q = 0; q < 4; ++q) pull += std::abs(l[q]);
  return std::sqrt(dx * dx + dy * dy + dm * dm) + 1e-3 * pull + kSpinDrivePull * std::abs(l[4]);
}

// A held small share's ln multipliers at knot i: the held fit's to the power heldPower.
void heldKnot(const CorrectionFit& held, double heldPower, std::size_t i, double* lm) {
  for (int p = 0; p < kMultipliers; ++p) lm[p] = heldPower * std::log(held.m[i][p]);
}

// The combined correction along one direction of the grid: at each knot the multipliers
// (Multipliers) minimising spinError (force and moment weighed as for spin alone), by pattern
// search in their logarithms from the previous knot's (one continuous branch), with a small pull
// towards 1. `held` (a spin share s3 below calibration::kSmallSpinShare): the same xi
// share and sign's fit at the first spin share sA from it on; knots below smallShareFitFrom(g) take
// held's multipliers to the power s3 / sA (what linear interpolation in ln multiplier between no
// spin and sA gives there, so the knot changes nothing there) and the search goes on from them;
// every knot is costed with towardsFullSlip's blend.
CorrectionFit identifyDirection(const Options& o, ExactCache* exact, double g, const Ray& r,
                                const PatchCalibration& base, const CorrectionFit* held = nullptr,
                                double heldPower = 0.0) {
  const double mzPeak = peakMoment(exact, g, r, o.corrKnots);
  CorrectionFit fit;
  double lm[kMultipliers] = {};
  for (std::size_t i = 0; i < o.corrKnots.size(); ++i) {
    const double e = o.corrKnots[i];
    const Point x = exact->at(g, r, e);
    if (e == 0.0) {
      fit.m.push_back(kNoCorrection);
      fit.error.push_back(0.0);
      continue;
    }
    auto error = [&](const double* l) {
      return spinError(fastsimCorrected(o, g, r, e, base, expOf(l).data(), held != nullptr), x,
                       mzPeak);
    };
    if (held && e < smallShareFitFrom(g)) {
      heldKnot(*held, heldPower, i, lm);
      fit.m.push_back(expOf(lm));
      fit.error.push_back(error(lm));
      continue;
    }
    auto cost = [&](const double* l) {
      return knotCost(fastsimCorrected(o, g, r, e, base, expOf(l).data(), held != nullptr), x,
                      mzPeak, l);
    };
    const int dims = searchedMultipliers(e, lm);
    coordinateSearch(
        lm, dims, cost, [](const double*) { return true; }, std::numeric_limits<int>::max());
    fit.m.push_back(expOf(lm));
    fit.error.push_back(error(lm));
  }
  // The linear range (force within 10 % of mu fz) stays Kalker's FastSim's, after the fit has run
  // through it on one branch: nss's time term (chi) is identified on that linear response, and a
  // correction there moved the linear combined scene (combined1) away from the exact one.
  for (std::size_t i = 0; i < o.corrKnots.size() && o.corrKnots[i] <= kLinearEnd; ++i) {
    fit.m[i] = kNoCorrection;
    if (o.corrKnots[i] > 0.0)
      fit.error[i] = spinError(
          fastsimCorrected(o, g, r, o.corrKnots[i], base, kNoCorrection.data(), held != nullptr),
          exact->at(g, r, o.corrKnots[i]), mzPeak);
  }
  return fit;
}

// A smoothing sweep's refit of one direction (identifyCorrection): at each knot past the linear
// range and from `refitFrom` on, the multipliers minimising knotCost plus
// `weight` times their ln distance from `target` (the neighbouring directions' mean), by pattern
// search from the target, so that of the near-equal optima the one nearest the neighbours is
// taken. A held small share (`held`, `heldPower` as in identifyDirection) takes its knots below
// smallShareFitFrom(g) from the held fit as it is now.
void refitTowards(const Options& o, ExactCache* exact, double g, const Ray& r,
                  const PatchCalibration& base, const CorrectionFit* held, double heldPower,
                  const std::vector<Multipliers>& target, double weight, double refitFrom,
                  CorrectionFit* fit) {
  const double mzPeak = peakMoment(exact, g, r, o.corrKnots);
  for (std::size_t i = 0; i < o.corrKnots.size(); ++i) {
    const double e = o.corrKnots[i];
    if (e <= kLinearEnd || (!held && e < refitFrom)) continue;
    const Point x = exact->at(g, r, e);
    double lm[kMultipliers];
    if (held && e < smallShareFitFrom(g)) {
      heldKnot(*held, heldPower, i, lm);
    } else {
      auto cost = [&](const double* l) {
        double apart = 0.0;
        for (int q = 0; q < kMultipliers; ++q) apart += std::abs(l[q] - target[i][q]);
        return knotCost(fastsimCorrected(o, g, r, e, base, expOf(l).data(), held != nullptr), x,
                        mzPeak, l) +
               weight * apart;
      };
      std::copy(target[i].begin(), target[i].end(), lm);
      const int dims = searchedMultipliers(e, lm);
      coordinateSearch(
          lm, dims, cost, [](const double*) { return true; }, std::numeric_limits<int>::max());
    }
    fit->m[i] = expOf(lm);
    fit->error[i] =
        spinError(fastsimCorrected(o, g, r, e, base, fit->m[i].data(), held != nullptr), x, mzPeak);
  }
}

// The combined correction's rows (kinds c1, c2, c3, cs, c3x) on the table `base` (single kinds
// only).
void identifyCorrection(const Options& o, ExactCache* exact, double g, const PatchCalibration& cal,
                        std::string* rows, std::string* notes, std::string* log) {
  {
    double worst = 0.0;
    // By spin share, then xi share and sign. The shares from kSmallSpinShare on first: a share
    // below it holds, outside its fitted range, the first of them (identifyDirection).
    std::map<double, std::map<std::pair<double, int>, CorrectionFit>> byShare;
    const auto first = std::find_if(o.spinShares.begin(), o.spinShares.end(),
                                    [](double s3) { return s3 >= calibration::kSmallSpinShare; });
    for (bool small : {false, true})
      for (double s3 : o.spinShares) {
        if ((s3 < calibration::kSmallSpinShare) != small) continue;
        if (small && first == o.spinShares.end())
          throw std::runtime_error("--spin-shares: a share below 0.25 needs one from 0.25 on");
        for (double t : o.xiShares)
          for (int sign : {1, -1}) {
            if (sign < 0 && t >= 1.0) continue;  // no eta: one direction, written for both signs
            const CorrectionFit fit =
                small ? identifyDirection(o, exact, g, gridRay(s3, t, sign), cal,
                                          &byShare[*first].at({t, sign}), s3 / *first)
                      : identifyDirection(o, exact, g, gridRay(s3, t, sign), cal);
            const double w = *std::max_element(fit.error.begin(), fit.error.end());
            char line[120];
            std::snprintf(line, sizeof line, "a/b %g direction %s: worst knot error %.4f\n", g,
                          gridRay(s3, t, sign).name.c_str(), w);
            *log += line;
            worst = std::max(worst, w);
            byShare[s3][{t, sign}] = fit;
            if (t >= 1.0) byShare[s3][{t, -1}] = fit;
          }
      }
    // Smoothing sweeps (Jacobi: each direction against its neighbours' fits of the sweep before).
    // Five multipliers against three forces leave near-equal optima, and directions fitted alone
    // took different ones; the core interpolates between directions, and between two such fits the
    // forces missed (doc/calibrated_fastsim.md, "How it is identified").
    const std::size_t nS = o.spinShares.size(), nT = o.xiShares.size();
    for (int sweep = 0; o.smoothing > 0.0 && sweep < kSmoothingSweeps; ++sweep) {
      const auto before = byShare;
      worst = 0.0;
      // The small shares after the rest: they hold the first share's fit of this sweep. That
      // share keeps its own fit below kRoundSmallShareFitFrom, where small shares hold it: smoothed
      // there, it moved the moment of the shares between them (h5's Mz 4.9 -> 5.7 % of the peak).
      for (int pass = 0; pass < 2; ++pass)
        for (std::size_t a = 0; a < nS; ++a)
          for (std::size_t b = 0; b < nT; ++b)
            for (int sign : {1, -1}) {
              const double s3 = o.spinShares[a], t = o.xiShares[b];
              const bool small = s3 < calibration::kSmallSpinShare;
              if ((sign < 0 && t >= 1.0) || small != (pass == 1)) continue;
              // The neighbours along each share (no eta: both signs' next xi share); a multiplier
              // that acts on nothing (L1 without xi, L2 without eta) is left out of their mean.
              struct Neighbour {
                std::size_t a, b;
                int sign;
              };
              std::vector<Neighbour> around;
              auto add = [&](std::size_t a2, std::size_t b2, int sg) {
                around.push_back({a2, b2, sg});
              };
              if (a > 0) add(a - 1, b, sign);
              if (a + 1 < nS) add(a + 1, b, sign);
              if (b > 0) add(a, b - 1, sign);
              if (b + 1 < nT) add(a, b + 1, sign);
              if (t >= 1.0 && b > 0) add(a, b - 1, -1);
              std::vector<Multipliers> target(o.corrKnots.size());
              for (std::size_t i = 0; i < target.size(); ++i)
                for (int q = 0; q < kMultipliers; ++q) {
                  double sum = 0.0;
                  int n = 0;
                  for (const Neighbour& nb : around) {
                    const double tk = o.xiShares[nb.b];
                    if ((q == 0 && tk <= 0.0) || (q == 1 && tk >= 1.0)) continue;
                    sum += std::log(before.at(o.spinShares[nb.a]).at({tk, nb.sign}).m[i][q]);
                    ++n;
                  }
                  target[i][q] = n > 0 ? sum / n : 0.0;
                }
              CorrectionFit fit = before.at(s3).at({t, sign});
              refitTowards(o, exact, g, gridRay(s3, t, sign), cal,
                           small ? &byShare.at(*first).at({t, sign}) : nullptr, s3 / *first, target,
                           o.smoothing, s3 == *first ? kRoundSmallShareFitFrom : kLinearEnd, &fit);
              worst = std::max(worst, *std::max_element(fit.error.begin(), fit.error.end()));
              byShare[s3][{t, sign}] = fit;
              if (t >= 1.0) byShare[s3][{t, -1}] = fit;
            }
    }
    for (double s3 : o.spinShares) {
      std::map<std::pair<double, int>, CorrectionFit>& fits = byShare[s3];
      // Without xi (t = 0) L1 does nothing, without eta (t = 1) L2: there the multiplier takes its
      // neighbour's, so that between the grid's directions it is interpolated from one that was
      // fitted.
      for (int sign : {1, -1})
        for (std::size_t i = 0; i < o.corrKnots.size(); ++i) {
          if (nT > 1 && o.xiShares.front() == 0.0)
            fits[{0.0, sign}].m[i][0] = fits[{o.xiShares[1], sign}].m[i][0];
          if (nT > 1 && o.xiShares.back() == 1.0)
            fits[{1.0, sign}].m[i][1] = fits[{o.xiShares[nT - 2], sign}].m[i][1];
        }
      for (const auto& [key, fit] : fits)
        for (int p = 0; p < kMultipliers; ++p)
          for (std::size_t i = 0; i < o.corrKnots.size(); ++i) {
            char line[200];
            std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d,%g,%g,%d\n", g, code(p, true),
                          o.corrKnots[i], fit.m[i][p], fit.error[i], o.nx, s3, key.first,
                          key.second);
            *rows += line;
          }
    }
    char note[120];
    std::snprintf(note, sizeof note, "#   a/b %g combined correction: worst knot error %.4f\n", g,
                  worst);
    *notes += note;
  }
}

// One mesh's (fastsim_nx o.nx) identification at one a/b: its rows, the notes of its fit errors
// and its progress log. It needs no other a/b's or mesh's: one job of the parallel run.
struct RowFit {
  std::string rows, singleNotes, correctionNotes, log;
};
RowFit identifyRow(const Options& o, ExactCache* exact, double g) {
  RowFit out;
  std::string* const notes = &out.singleNotes;
  std::map<double, std::string> rows;  // this a/b's rows (rows[g]), as the CSV table holds them
  {
    std::vector<double> couple;  // eta's fit's lateral coupling, which spin's is fitted on
    for (int kind = 0; kind < 3; ++kind) {
      const KindFit fit = kind == 2                 ? identifySpin(o, exact, g, {})
                          : kind == 1 && o.coupling ? identifyLateral(o, exact, g)
                                                    : identifyKind(o, exact, g, kind);
      if (kind == 1) couple = fit.couple;
      double worst = 0.0;
      for (std::size_t i = 0; i < o.knots.size(); ++i) {
        char line[160];
        std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d\n", g, kRays[kind].name.c_str(),
                      o.knots[i], fit.ratio[i], fit.error[i], o.nx);
        rows[g] += line;
        worst = std::max(worst, fit.error[i]);
      }
      for (std::size_t i = 0; i < fit.couple.size(); ++i) {  // eta's coupling, its fit's error
        char line[160];
        std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d\n", g, code(kEtaCoupling),
                      o.knots[i], fit.couple[i], fit.error[i], o.nx);
        rows[g] += line;
      }
      if (kind == 2)  // spin's second parameter: same knots, the same fit's error
        for (std::size_t i = 0; i < o.knots.size(); ++i) {
          char line[160];
          std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d\n", g, code(kSpinDriveRatio),
                        o.knots[i], fit.ratioX[i], fit.error[i], o.nx);
          rows[g] += line;
        }
      if (kind == 2)
        for (std::size_t i = 0; i < o.knots.size(); ++i) {
          char line[160];
          std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d\n", g, code(kSpinBoundShape),
                        o.knots[i], fit.shape, fit.error[i], o.nx);
          rows[g] += line;
        }
      char note[120];
      std::snprintf(note, sizeof note, "#   a/b %g kind %s: worst knot error %.4f\n", g,
                    kRays[kind].name.c_str(), worst);
      *notes += note;
    }
    if (o.coupling && o.etaSlope) {  // on the single kinds' table at this a/b
      std::stringstream single;
      single << "a_over_b,kind,epsilon,ratio,fit_error,fastsim_nx\n" << rows[g];
      std::vector<double> error;
      std::vector<double> beta = identifyEtaSlope(
          o, exact, g, CalibrationTable::parse(single, "(single kinds)").at(g), &error);
      auto write = [&](int kind, const std::vector<double>& v) {
        for (std::size_t i = 0; i < v.size(); ++i) {
          char line[160];
          std::snprintf(line, sizeof line, "%g,%s,%g,%.6f,%.5f,%d\n", g, code(kind), o.knots[i],
                        v[i], error[i], o.nx);
          rows[g] += line;
        }
      };
      if (o.etaNoSpin) {  // on the single kinds' table with that slope as its start
        std::stringstream withSlope;
        withSlope << "a_over_b,kind,epsilon,ratio,fit_error,fastsim_nx\n" << rows[g];
        for (std::size_t i = 0; i < beta.size(); ++i)
          withSlope << g << "," << code(kEtaDriveSlope) << "," << o.knots[i] << "," << beta[i]
                    << ",0," << o.nx << "\n";
        const EtaNoSpinFit fit = identifyEtaWithoutSpin(
            o, exact, g, CalibrationTable::parse(withSlope, "(single kinds)").at(g));
        beta = fit.beta;
        error = fit.error;
        write(kEtaRatioNoSpin, fit.ratio);
        write(kEtaCouplingNoSpin, fit.couple);
        write(kEtaBoundShapeNoSpin, fit.shape);
      }
      write(kEtaDriveSlope, beta);
      char note[120];
      std::snprintf(note, sizeof note, "#   a/b %g kind%s: worst knot error %.4f\n", g,
                    o.etaNoSpin ? "s 22n, 22cn, 22s, 22b (together)" : " 22b",
                    *std::max_element(error.begin(), error.end()));
      *notes += note;
    }
  }
  out.rows = rows[g];
  if (!o.spinShares.empty()) {  // the correction on top of the single kinds' table
    std::stringstream single;
    single << "a_over_b,kind,epsilon,ratio,fit_error,fastsim_nx\n" << out.rows;
    identifyCorrection(o, exact, g, CalibrationTable::parse(single, "(single kinds)").at(g),
                       &out.rows, &out.correctionNotes, &out.log);
  }
  return out;
}

bool isBinaryPath(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".bin") == 0;
}

// The summary beside a binary table: FILE.bin's is FILE_summary.txt.
std::string summaryPath(const std::string& bin) {
  return bin.substr(0, bin.size() - 4) + "_summary.txt";
}

// Writes `table` to `path`: the binary format where it ends in .bin, else CSV.
void writeTableFile(const CalibrationTable& table, const std::string& path) {
  std::ofstream out = tools::writeFile(path);
  if (isBinaryPath(path))
    table.writeBinary(out);
  else
    table.writeCsv(out);
  if (!out.flush()) throw std::runtime_error("cannot write " + path);
}

// Runs job(i) for i in [0, n) on `threads` threads, in the order of `order` (the longest jobs
// first, so that the threads end together). Each job writes only its own result: what the run
// makes does not depend on the number of threads. The first exception is rethrown.
template <class Job>
void runJobs(std::size_t n, int threads, const std::vector<std::size_t>& order, const Job& job) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failed;
  std::mutex failedMutex;
  auto work = [&] {
    for (std::size_t k; (k = next++) < n;) {
      try {
        job(order[k]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failedMutex);
        if (!failed) failed = std::current_exception();
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

void writeTable(const Options& o, ExactCache* exact, int argc, char** argv) {
  // One job per mesh and a/b, the meshes' blocks and notes assembled in order afterwards.
  std::vector<std::pair<int, double>> jobs;
  for (int nx : o.meshes)
    for (double g : o.ratios) jobs.push_back({nx, g});
  std::vector<RowFit> fits(jobs.size());
  // The march's cost grows as nx^2: the finest meshes first.
  std::vector<std::size_t> order(jobs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return jobs[x].first > jobs[y].first; });
  std::mutex logMutex;
  runJobs(jobs.size(), o.threads, order, [&](std::size_t i) {
    Options m = o;
    m.nx = jobs[i].first;
    fits[i] = identifyRow(m, exact, jobs[i].second);
    std::lock_guard<std::mutex> lock(logMutex);
    std::cout << "FastSim " << m.nx << "x" << m.nx << " a/b " << jobs[i].second << ":\n"
              << fits[i].log << std::flush;
  });
  std::string blocks;
  std::ostringstream notes;
  for (std::size_t m = 0; m < o.meshes.size(); ++m) {
    const int nx = o.meshes[m];
    const std::string title =
        "# FastSim mesh " + std::to_string(nx) + "x" + std::to_string(nx) + "\n";
    // The a/b rows in increasing a/b (the table's order), the notes in --ab's.
    std::map<double, std::string> rows;
    std::string single, correction;
    for (std::size_t r = 0; r < o.ratios.size(); ++r) {
      const RowFit& fit = fits[m * o.ratios.size() + r];
      rows[o.ratios[r]] = fit.rows;
      single += fit.singleNotes;
      correction += fit.correctionNotes;
    }
    notes << title << single << correction;
    blocks += title;
    for (const auto& [g, text] : rows) blocks += text;
  }
  std::string command = "identify_calibration";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  std::ostringstream head;
  head << "# Calibrated FastSim: flexibility ratio per creepage kind against normalised creepage\n"
       << "# (src/core/calibration/calibration_table.hpp). Identified " << date
       << " by: " << command << "\n# against our exact solver (" << o.grid << "x" << o.grid
       << ", nu " << o.nu << "; exact curves cached in " << o.exact
       << ") per FastSim mesh (fastsim_nx; a model "
       << "interpolates between the meshes in 1/nx, the nearest beyond them); other nu: the same "
          "ratios.\n"
       << "# fit_error (and the worst knot errors below): max(|dFx|, |dFy|) / (mu fz) at the knot "
          "(spin, kinds 23 and 23x fitted "
          "together, and the combined correction c1, c2, c3, cs, c3x: the larger of that and 0.2 "
          "|dMz| / "
          "peak |Mz|)\n"
       << notes.str();
  const std::string table =
      "a_over_b,kind,epsilon,ratio,fit_error,fastsim_nx,spin_share,xi_share,sign\n" + blocks;
  if (isBinaryPath(o.out)) {
    // The binary table, and beside it what is not runtime data: the command and the fit errors.
    std::istringstream text(table);
    writeTableFile(CalibrationTable::parse(text, "(identified)"), o.out);
    tools::writeFile(summaryPath(o.out)) << head.str();
  } else {
    tools::writeFile(o.out) << head.str() << table;
  }
  std::cout << notes.str();
}

// Curves and their errors per a/b and ray: exact, classic, calibrated.
void writeCurves(const Options& o, ExactCache* exact, const CalibrationTable& meshes) {
  const CalibrationTable table = meshes.forMesh(o.nx);
  std::ofstream out;
  if (!o.curves.empty()) {
    out = tools::writeFile(o.curves);
    out << "# Steady creep curves, exact (" << o.grid << "x" << o.grid << ") / classic FastSim / "
        << "calibrated FastSim (" << o.nx << "x" << o.nx
        << "); made by identify_calibration --curves\n"
        << "# fx, fy over mu fz; mz over mu fz sqrt(ab); epsilon: normalised creepage\n"
        << "a_over_b,ray,epsilon,xi,eta,phi,fx_exact,fy_exact,mz_exact,fx_classic,fy_classic,"
           "mz_classic,fx_calibrated,fy_calibrated,mz_calibrated\n";
  }
  std::printf("FastSim %dx%d\n", o.nx, o.nx);
  std::printf("%-5s %-5s %9s %9s %9s %9s   (force: max |dF| / mu fz; Mz: max |dMz| / peak |Mz|)\n",
              "a/b", "ray", "F clas", "F cal", "Mz clas", "Mz cal");
  for (double g : o.ratios) {
    const PatchCalibration cal = table.at(g);
    for (const Ray& r : kRays) {
      double fErr[2] = {0, 0}, mErr[2] = {0, 0}, peak = 0.0;
      std::vector<Point> x, c[2];
      for (double e : o.points) {
        x.push_back(exact->at(g, r, e));
        c[0].push_back(fastsimAt(o, g, r, e, PatchCalibration()));
        c[1].push_back(fastsimAt(o, g, r, e, cal));
        peak = std::max(peak, std::abs(x.back().mz));
      }
      for (std::size_t i = 0; i < x.size(); ++i) {
        for (int v = 0; v < 2; ++v) {
          fErr[v] = std::max(fErr[v], pointError(c[v][i], x[i], 0.0));
          mErr[v] = std::max(mErr[v], std::abs(c[v][i].mz - x[i].mz) / peak);
        }
        if (out) {
          const Creepages k = Setup(o, g).creepages(r, o.points[i]);
          char line[400];
          std::snprintf(line, sizeof line,
                        "%g,%s,%g,%.6g,%.6g,%.6g,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", g,
                        r.name.c_str(), o.points[i], k.xi, k.eta, k.phi, x[i].fx, x[i].fy, x[i].mz,
                        c[0][i].fx, c[0][i].fy, c[0][i].mz, c[1][i].fx, c[1][i].fy, c[1][i].mz);
          out << line;
        }
      }
      if (peak > 1e-3)
        std::printf("%-5g %-5s %9.4f %9.4f %9.4f %9.4f\n", g, r.name.c_str(), fErr[0], fErr[1],
                    mErr[0], mErr[1]);
      else  // no spin moment to speak of (xi alone)
        std::printf("%-5g %-5s %9.4f %9.4f %9s %9s\n", g, r.name.c_str(), fErr[0], fErr[1], "-",
                    "-");
    }
  }
}

// The moment study (--moment-study). Steady FastSim on the table's step with its flexibilities L1,
// L2, L3 (L3x with L3) times exp(l[0..2]) and its bound's shape times exp(l[3]) (where the table
// has no shape, exp(l[3]) - 1 from the parabola), and with two terms the core's march does not
// have:
// - an eta drive varying along each strip, (eta / L2) (1 - beta x / a_j) / (1 - beta / 3) (x
//   rolling, leading edge at +a_j): in adhesion the same force, its moment times 1 / (1 - beta /
//   3);
// - a longitudinal slip from the lateral traction: du_x/dx = L1 dtau_x/dx + (couple / G) (y / b)
//   tau_y, so the x drive gains couple (y / b) tau_y / (G L1), tau_y the upstream node's traction.
//   A local stand-in for the longitudinal surface displacement that lateral traction makes through
//   nu (Cerruti's solution), odd in y: in full slip it turns the traction off the rigid slip's
//   direction and carries a moment, as exact theory's, which is zero at nu = 0.
// Its own march, a strip at a time (the core's is untouched); with l = 0, beta = 0 and couple = 0
// it is the core's steady FastSim (the study prints the difference).
struct StudyTerms {
  double l[4] = {0.0, 0.0, 0.0, 0.0};
  double beta = 0.0, couple = 0.0;
};

Point studyFastSim(const Options& o, double g, const Ray& r, double e, const PatchCalibration& base,
                   const StudyTerms& t) {
  const Setup s(o, g);
  Scratch& scratchField = scratch(o.nx, s.a, s.b);
  const PatchMesh& mesh = scratchField.mesh;
  TractionField& f = scratchField.f;
  const Creepages c = s.creepages(r, e);
  const CalibratedStep step = base.step(s.a, s.b, s.G, s.k, s.mu * s.fz, c);
  const double shape =
      step.boundShape > 0.0 ? step.boundShape * std::exp(t.l[3]) : std::exp(t.l[3]) - 1.0;
  scratchField.bound(s.fz, s.mu, std::min(calibration::kMaxBoundShape, std::max(0.0, shape)));
  const double L1 = step.L.L1 * std::exp(t.l[0]), L2 = step.L.L2 * std::exp(t.l[1]),
               L3 = step.L.L3 * std::exp(t.l[2]), L3x = step.L.spinX() * std::exp(t.l[2]);
  const double gy = c.eta / L2 / (1.0 - t.beta / 3.0), gphi = c.phi / L3;
  double fx = 0.0, fy = 0.0, mz = 0.0;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dx = mesh.stripStep(j), aj = mesh.stripHalfLength(j), y = mesh.stripY(j);
    const double sx = c.xi / L1 - c.phi * y / L3x, perTy = t.couple * (y / s.b) / (s.G * L1);
    double tx = 0.0, ty = 0.0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const UpstreamStep u(i, dx, aj);
      tx -= u.h * (sx + perTy * ty);
      ty -= u.h * (gy * (1.0 - t.beta * u.xMid / aj) + gphi * u.xMid);
      const double bound = f.bound(mesh.index(i, j)), size = std::hypot(tx, ty);
      if (size > bound) {
        tx *= bound / size;
        ty *= bound / size;
      }
      fx += tx * mesh.nodeArea(j);
      fy += ty * mesh.nodeArea(j);
      mz += (mesh.nodeX(i, j) * ty - y * tx) * mesh.nodeArea(j);
    }
  }
  return s.normalised(fx, fy, mz);
}

// Errors of one ray: the largest max(|dFx|, |dFy|) / (mu fz) and |dMz| / peak |Mz| over its points.
struct RayError {
  double f = 0.0, mz = 0.0;
};

// At a point, the study's parameters that fit the exact one best (the combined correction's smooth
// norm and pull, identifyDirection), by pattern search from t: l[0..3], with `beta` the eta
// drive's slope as well; the coupling as given.
StudyTerms fitPoint(const Options& o, double g, const Ray& r, double e, const Point& x,
                    double mzPeak, const PatchCalibration& base, StudyTerms t, bool beta) {
  // The search's point: l[0..3], then beta when it is searched too.
  const int dims = beta ? 5 : 4;
  auto terms = [&](const double* v) {
    StudyTerms u = t;
    std::copy(v, v + 4, u.l);
    if (beta) u.beta = v[4];
    return u;
  };
  auto cost = [&](const double* v) {
    const StudyTerms u = terms(v);
    const Point p = studyFastSim(o, g, r, e, base, u);
    const double dm = mzPeak > 1e-3 ? 0.2 * (p.mz - x.mz) / mzPeak : 0.0;
    return std::sqrt((p.fx - x.fx) * (p.fx - x.fx) + (p.fy - x.fy) * (p.fy - x.fy) + dm * dm) +
           1e-3 * (std::abs(u.l[0]) + std::abs(u.l[1]) + std::abs(u.l[2]) + std::abs(u.l[3]) +
                   std::abs(u.beta));
  };
  // The shape at most about 1 where the table has none; beta in [-2, 2.5] (1 - beta / 3 > 0).
  auto allowed = [&](const double* v) {
    const StudyTerms u = terms(v);
    return !(u.l[3] > 0.7 || u.beta > 2.5 || u.beta < -2.0);
  };
  double v[kMaxSearchDims] = {t.l[0], t.l[1], t.l[2], t.l[3], t.beta};
  coordinateSearch(v, dims, cost, allowed, 500);
  return terms(v);
}

// The coupling (and L2's multiplier, on a grid; with `all` one multiplier of L1, L2 and L3) that
// fits ray 22's exact point x best: the larger of max(|dFx|, |dFy|) and 0.2 |dMz| / peak.
StudyTerms fitCoupling(const Options& o, double g, double e, const Point& x, double mzPeak,
                       const PatchCalibration& base, bool all) {
  double best = 1e300;
  StudyTerms fit;
  for (int ic = -150; ic <= 50; ++ic)
    for (int il = -15; il <= 15; ++il) {
      StudyTerms t;
      t.couple = 0.01 * ic;
      t.l[1] = 0.02 * il;
      if (all) t.l[0] = t.l[2] = t.l[1];
      const Point p = studyFastSim(o, g, kRays[1], e, base, t);
      const double c = std::max(std::max(std::abs(p.fx - x.fx), std::abs(p.fy - x.fy)),
                                0.2 * std::abs(p.mz - x.mz) / mzPeak);
      if (c < best) best = c, fit = t;
    }
  return fit;
}

// Per a/b: the coupling that fits eta alone (ray 22) point by point (with L2's multiplier, on a
// grid), then every ray's errors on the table; refitted (l); refitted with beta; with that
// coupling on the table as it is; refitted with it; refitted with beta and it; and "tabulated": the
// coupling and one multiplier of L1, L2, L3 fitted on 22 at the table's knots (--knots),
// interpolated linearly in e, the multiplier weighed by eta's share of e^2 (as 22's ratio acts in
// the table), nothing else refitted: what a table kind would give on the rays off its knots.
void momentStudy(const Options& o, ExactCache* exact, const CalibrationTable& meshes) {
  const CalibrationTable table = meshes.forMesh(o.nx);
  std::printf("FastSim %dx%d; force: max |dF| / mu fz, Mz: max |dMz| / peak |Mz|, over --points\n",
              o.nx, o.nx);
  for (double g : o.ratios) {
    const PatchCalibration cal = table.at(g);
    auto peakOf = [&](const Ray& r) { return peakMoment(exact, g, r, o.points); };
    // The couplings of ray 22 at the points, and how far the study's march is from the core's.
    const double peak22 = peakOf(kRays[1]);
    std::vector<double> couple;
    double march = 0.0;
    for (double e : o.points) {
      couple.push_back(fitCoupling(o, g, e, exact->at(g, kRays[1], e), peak22, cal, false).couple);
      for (const Ray& r : kRays) {
        const Point p = studyFastSim(o, g, r, e, cal, StudyTerms()), q = fastsimAt(o, g, r, e, cal);
        march =
            std::max({march, std::abs(p.fx - q.fx), std::abs(p.fy - q.fy), std::abs(p.mz - q.mz)});
      }
    }
    // The same at the table's knots, with one multiplier of L1, L2, L3 (as 22's ratio acts in the
    // table): the coupling and the ratio a table kind would hold, interpolated at the points.
    std::vector<double> knotCouple, knotLog;
    for (double e : o.knots) {
      if (e == 0.0) {
        knotCouple.push_back(0.0);  // linear theory: the first knot's, below
        knotLog.push_back(0.0);
        continue;
      }
      const StudyTerms t = fitCoupling(o, g, e, exact->at(g, kRays[1], e), peak22, cal, true);
      knotCouple.push_back(t.couple);
      knotLog.push_back(t.l[1]);
    }
    if (knotCouple.size() > 1) knotCouple[0] = knotCouple[1];
    auto tabulated = [&](const std::vector<double>& v, double e) {
      if (!(e < o.knots.back())) return v.back();
      std::size_t i = 1;
      while (o.knots[i] <= e) ++i;
      const double w = (e - o.knots[i - 1]) / (o.knots[i] - o.knots[i - 1]);
      return v[i - 1] + w * (v[i] - v[i - 1]);
    };
    std::printf("a/b %g: coupling fitted on ray 22 at each point:", g);
    for (double c : couple) std::printf(" %.2f", c);
    std::printf(" (study march against the core's: %.1e)\n", march);
    std::printf("a/b %g: at the knots, coupling / multiplier:", g);
    for (std::size_t i = 0; i < o.knots.size(); ++i)
      std::printf(" %g: %.2f / %.2f", o.knots[i], knotCouple[i], std::exp(knotLog[i]));
    std::printf("\n");
    std::printf("%-5s %-5s %15s %15s %15s %15s %15s %15s %15s\n", "a/b", "ray", "table F / Mz",
                "refit", "refit, beta", "coupled", "refit, coupled", "beta, coupled", "tabulated");
    for (const Ray& r : kRays) {
      const double peak = peakOf(r);
      constexpr int kVariants = 7;
      RayError err[kVariants];
      for (std::size_t i = 0; i < o.points.size(); ++i) {
        const double e = o.points[i];
        const Point x = exact->at(g, r, e);
        StudyTerms coupled;
        coupled.couple = couple[i];
        // As a table would: the knots' coupling at e, and their multiplier by eta's share of e^2
        // (the table's ln ratio is the kinds' ln ratios weighed by their shares).
        auto knotTerms = [&](const Ray& ray, double at) {
          StudyTerms t;
          const double n2 = ray.e[0] * ray.e[0] + ray.e[1] * ray.e[1] + ray.e[2] * ray.e[2];
          t.couple = tabulated(knotCouple, at);
          t.l[0] = t.l[1] = t.l[2] = ray.e[1] * ray.e[1] / n2 * tabulated(knotLog, at);
          return t;
        };
        const StudyTerms terms[kVariants] = {
            StudyTerms(),
            fitPoint(o, g, r, e, x, peak, cal, StudyTerms(), false),
            fitPoint(o, g, r, e, x, peak, cal, StudyTerms(), true),
            coupled,
            fitPoint(o, g, r, e, x, peak, cal, coupled, false),
            fitPoint(o, g, r, e, x, peak, cal, coupled, true),
            knotTerms(r, e)};
        for (int v = 0; v < kVariants; ++v) {
          const Point p = studyFastSim(o, g, r, e, cal, terms[v]);
          err[v].f = std::max({err[v].f, std::abs(p.fx - x.fx), std::abs(p.fy - x.fy)});
          if (peak > 1e-3) err[v].mz = std::max(err[v].mz, std::abs(p.mz - x.mz) / peak);
        }
      }
      std::printf("%-5g %-5s", g, r.name.c_str());
      for (const RayError& v : err)
        if (peak > 1e-3)
          std::printf("  %.4f / %5.3f", v.f, v.mz);
        else
          std::printf("  %.4f /     -", v.f);
      std::printf("\n");
    }
  }
}

// Solves (or finds in the cache) every exact point the combined correction is identified on and
// evaluated on, saving the cache as it goes (a long job).
void solveGrid(const Options& o, ExactCache* exact) {
  int last = 0;
  for (double g : o.ratios) {
    std::vector<std::pair<Ray, std::vector<double>>> jobs;
    for (const Ray& r : gridRays(o)) jobs.push_back({r, o.corrKnots});
    if (!o.gridOnly)
      for (const Ray& r : kRays) jobs.push_back({r, o.points});
    for (const auto& [r, es] : jobs)
      for (double e : es) {
        if (e > 0.0) exact->at(g, r, e);
        if (exact->solved() >= last + 20) {
          last = exact->solved();
          exact->save();
          std::cout << "a/b " << g << " " << r.name << ": " << last << " solved" << std::endl;
        }
      }
  }
  exact->save();
}

int run(const Options& o, int argc, char** argv) {
  if (!o.convert.empty()) {  // a table file into another format: no exact curves needed
    if (o.out.empty()) throw std::runtime_error("--convert: --out FILE");
    writeTableFile(CalibrationTable::load(o.convert), o.out);
    return 0;
  }
  if (o.dump >= 0) {
    const CalibrationTable table =
        o.table.empty() ? CalibrationTable::shipped() : CalibrationTable::load(o.table);
    if (o.out.empty()) {
      table.writeCsv(std::cout, o.dump);
    } else {
      std::ofstream out = tools::writeFile(o.out);
      table.writeCsv(out, o.dump);
    }
    return 0;
  }
  if (o.meshes.empty()) throw std::runtime_error("--nx: at least one mesh");
  for (int nx : o.meshes)
    if (nx < 2) throw std::runtime_error("--nx: every mesh needs at least 2 nodes per axis");
  if (!o.curves.empty() && o.meshes.size() != 1)
    throw std::runtime_error("--curves: one --nx (the curves file holds one mesh)");
  // The default cache is relative to the repository root: run elsewhere, the tool would find no
  // cache and start solving every point (hours). A new cache is asked for by name.
  if (o.exact == kDefaultExact && !std::ifstream(o.exact))
    throw std::runtime_error(std::string("no exact cache ") + kDefaultExact +
                             " here: run from the repository root, or give --exact FILE (a new "
                             "cache is started where FILE does not exist)");
  ExactCache exact(o.exact, o);
  struct Saver {  // keeps what was solved even when a later step throws
    ExactCache* c;
    ~Saver() { c->save(); }
  } saver{&exact};
  if (o.solveGrid) {
    solveGrid(o, &exact);
    return 0;
  }

  if (o.momentStudy) {
    if (o.meshes.size() != 1) throw std::runtime_error("--moment-study: one --nx");
    Options m = o;
    m.nx = o.meshes.front();
    momentStudy(m, &exact,
                o.table == "classic" ? CalibrationTable()
                : o.table.empty()    ? CalibrationTable::shipped()
                                     : CalibrationTable::load(o.table));
    return 0;
  }
  if (!o.out.empty()) writeTable(o, &exact, argc, argv);
  const std::string path = !o.out.empty() ? o.out : o.table;  // empty: the shipped table
  const CalibrationTable table = path == "classic" ? CalibrationTable()
                                 : path.empty()    ? CalibrationTable::shipped()
                                                   : CalibrationTable::load(path);
  for (int nx : o.meshes) {
    Options m = o;
    m.nx = nx;
    writeCurves(m, &exact, table);
  }
  std::cout << "exact points solved (not in the cache): " << exact.solved() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("identify_calibration", argc, argv, addOptions,
                                 [&](const Options& o) { return run(o, argc, argv); });
}
