// The creep-force models on the true patch (StepInput::shape) against the exact half-space
// solver's steady tangential solution on the exact normal solution, on every patch of the
// Manchester benchmark's case A-2.2 (validation/manchester_a22.hpp), both wheels, at the case's
// own creepages. Per patch: the exact forces, and the errors over mu Fn (exact) of steady FastSim
// on the equivalent ellipse (today's), on our strips with the two bound rules (StripBound), the
// calibrated variant on our strips, nss's steady limit on our strips, and steady FastSim on the
// exact solution's own strips (its grid columns: the tangential model alone). doc/true_patch.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/exact/halfspace_solver.hpp"
#include "core/fastsim/fastsim.hpp"
#include "tool_options.hpp"
#include "validation/ellipse_patch.hpp"
#include "validation/manchester_a22.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string cases = "test/data/profiles/a22_cases.csv";
  std::string out = "doc/data/true_patch_a22.csv";
  int exact_mx = 40, exact_my = 32;
  int nx = 20;
  double mu = 0.3;
  bool sliding = false;
  bool continuous_region = NormalOptions{}.continuous_region;
};

void addOptions(CLI::App& app, Options* o) {
  app.description(
      "Creep forces on the true patch against the exact steady tangential solution, Manchester "
      "A-2.2, every case and wheel.");
  tools::option(app, "--cases", &o->cases, "the benchmark's wheelset states (a22_cases.csv)");
  tools::option(app, "--out", &o->out, "the table, one row per case, wheel and patch");
  tools::option(app, "--exact-mx", &o->exact_mx, "exact grid: elements along x per patch");
  tools::option(app, "--exact-my", &o->exact_my, "exact grid: elements across per patch");
  tools::option(app, "--nx", &o->nx, "FastSim nodes per strip");
  tools::option(app, "--mu", &o->mu, "friction coefficient");
  app.add_flag_callback(
      "--no-continuous-region", [o] { o->continuous_region = false; },
      "the normal problem with NormalOptions::continuous_region = false (its rule before "
      "continuous_region became the default)");
  app.add_flag("--sliding", o->sliding,
               "instead: an ellipse sliding sideways against the exact transient solution of the "
               "same motion, nss with the history's frame following 0, 1/2 (the model's) and all "
               "of the contact point's move (doc/true_patch.md, History)");
}

struct Forces {
  double fx = 0.0, fy = 0.0, mz = 0.0;
};

double heldAOverB(double a, double b) {
  return std::min(std::max(a / b, kKalkerMinAOverB), kKalkerMaxAOverB);
}

// Steady classic FastSim on the shape's strips with bound rule `rule` (or on the ellipse a, b when
// shape is null), Kalker's flexibilities of the ellipse (a/b held in the table).
Forces steadyOn(const PatchShape* shape, StripBound rule, double a, double b, double fn,
                const Creepages& c, const Options& o, double G, double nu) {
  PatchMesh mesh(o.nx, o.nx, a, b);
  if (shape) mesh.setStrips(o.nx, *shape, a, b, rule);
  TractionField f;
  f.resize(mesh.size());
  parabolicBound(mesh, a, b, fn, o.mu, &f);
  const Flexibilities L = kalkerFlexibilities(a, b, G, kalkerCoefficients(heldAOverB(a, b), nu));
  const CreepForces r = steadyFastSim(mesh, L, c, &f);
  return {r.fx, r.fy, r.mz};
}

// A model of ContactParameters through its public interface on the shape; `steps` constant
// steps (the steady limit of a transient model).
Forces modelOn(const std::string& model, FastSimVariant v, const PatchShape& shape, double a,
               double b, double fn, const Creepages& c, const Options& o, double G, double nu,
               int steps, std::string* message) {
  ContactParameters p;
  p.model = model;
  p.mesh = "adaptive";
  p.fastsim = v;
  p.nx = p.ny = o.nx;
  p.G = G;
  p.nu = nu;
  p.mu = o.mu;
  p.b0 = b;
  p.a0 = std::min(std::max(a / b, kKalkerMinAOverB * (1.0 + 1e-12)),
                  kKalkerMaxAOverB * (1.0 - 1e-12)) *
         b;  // just inside the table: a0 / b0 rounds back onto it
  p.fz0 = fn;
  auto m = makeContactModel(p);
  StepInput in;
  in.V = 2.0;
  in.dt = 0.1 * a / in.V;
  in.xi = c.xi;
  in.eta = c.eta;
  in.phi = c.phi;
  in.fz = fn;
  in.a = a;
  in.b = b;
  in.shape = &shape;
  StepOutput out;
  for (int k = 0; k < steps; ++k) out = m->step(in);
  if (out.status != StepStatus::kOk) *message = out.message;
  return {out.fx, out.fy, out.mz};
}

// The exact solution's strips: each grid column's loaded extent (symmetric about x = 0, as the
// gap is) and peak pressure, eta from the candidate's point; *a, *b its equivalent ellipse (b half
// the lateral extent, pi a b the area), as the normal problem gives ours.
PatchShape exactStrips(const A22Exact& e, double* a, double* b) {
  PatchShape s;
  double area = 0.0;
  const HalfspaceGrid& g = e.grid;
  for (int iy = 0; iy < g.my; ++iy) {
    double L = 0.0, pmax = 0.0;
    for (int ix = 0; ix < g.mx; ++ix) {
      const double p = e.p(g.index(ix, iy));
      if (p > 0.0) {
        L = std::max(L, std::abs(g.xc(ix)) + 0.5 * g.dx);
        pmax = std::max(pmax, p);
      }
    }
    if (L > 0.0) s.strips.push_back(PatchStrip{e.eta_offset + g.yc(iy), g.dy, L, -L, pmax});
    area += 2.0 * L * g.dy;
  }
  *b = s.strips.empty()
           ? 0.0
           : 0.5 * (s.strips.back().eta - s.strips.front().eta + s.strips.back().width);
  *a = *b > 0.0 ? area / (M_PI * *b) : 0.0;
  return s;
}

// An ellipse (6 x 4 mm, 80 kN) sliding sideways `speed` b per element rolled for 40 elements
// after 60 at rest, then 40 more at rest, at constant creepages, its reference point moving with
// it: nss on its strips against the exact transient solution (the pressure moved across a fixed
// 24-element grid, the history at fixed points of the rail). nss carries its history in a frame
// following half the point's move (kCarriedShare): given the origin times 2 share, it carries
// it as a frame following `share` of the move would. Worst |F - F_exact| and worst |F| - |F_exact|
// over mu fz from the slide's start.
void slide(double speed, double share, const Creepages& w, const Options& o, double* worst,
           double* above) {
  const double a = 6e-3, b = 4e-3, fz = 8e4, G = 8.2e10, nu = 0.28;
  const int settle = 60, moving = 40;
  const double travel = speed * b * moving;
  const HalfspaceGrid g = ellipseSlideGrid(a, b, travel);
  HalfspaceSolver exact(g, G, nu);
  ContactParameters p;
  p.model = "nss";
  p.mesh = "adaptive";
  p.a0 = a;
  p.b0 = b;
  p.fz0 = fz;
  p.nx = p.ny = o.nx;
  p.mu = o.mu;
  auto nss = makeContactModel(p);
  *worst = *above = 0.0;
  for (int k = 0; k < settle + moving + 40; ++k) {
    const double s = -0.5 * travel + speed * b * std::min(std::max(k - settle, 0), moving);
    exact.setPressure(movedEllipsePressure(g, a, b, fz, s));
    const HalfspaceSolution& x =
        exact.solve(RollingMode::kTransient, Creepages{w.xi + w.phi * s, w.eta, w.phi}, o.mu);
    const PatchShape shape = ellipseStrips(a, b, fz, o.nx, 2.0 * share * s);
    StepInput in;
    in.V = 2.0;
    in.dt = g.dx / in.V;
    in.xi = w.xi;
    in.eta = w.eta;
    in.phi = w.phi;
    in.fz = fz;
    in.a = a;
    in.b = b;
    in.shape = &shape;
    const StepOutput out = nss->step(in);
    if (k < settle) continue;
    *worst = std::max(*worst, std::hypot(out.fx - x.fx, out.fy - x.fy) / (o.mu * fz));
    *above = std::max(*above, (std::hypot(out.fx, out.fy) - std::hypot(x.fx, x.fy)) / (o.mu * fz));
  }
}

int runSliding(const Options& o) {
  const Creepages scenes[4] = {
      {1e-3, 5e-4, 0.3}, {0.0, 2e-3, 0.0}, {-2e-3, 0.0, 1.0}, {3e-4, -2e-4, 0.0}};
  std::printf("%-28s %5s %6s  %s\n", "creepages (xi, eta, phi)", "share", "b/el.",
              "worst |F - F_exact|, worst |F| - |F_exact| over mu fz");
  for (const Creepages& w : scenes)
    for (double share : {0.0, 0.5, 1.0})
      for (double speed : {0.003, 0.01, 0.03, 0.1}) {
        double worst = 0.0, above = 0.0;
        slide(speed, share, w, o, &worst, &above);
        std::printf("%8.1e %8.1e %8.2f %5.1f %6.3f  %.4f %.4f\n", w.xi, w.eta, w.phi, share, speed,
                    worst, above);
      }
  return 0;
}

int run(const Options& o) {
  if (o.sliding) return runSliding(o);
  const std::vector<A22State> states = readA22States(o.cases);
  A22Options ao;
  ao.exact_mx = o.exact_mx;
  ao.exact_my = o.exact_my;
  ao.normal.continuous_region = o.continuous_region;
  const ContactSearch search{WheelsetTrackData{}};
  std::ofstream out = tools::writeFile(o.out);
  out << "wheel,y_mm,patch,zone,method,a_over_b,fn_N,exact_fn_N,xi,eta,phi_per_m,exact_fx_N,"
         "exact_fs_N,exact_mz_Nm,ellipse_dfx,ellipse_dfs,strips_dfx,strips_dfs,strips_dmz,"
         "strip_force_dfx,strip_force_dfs,calibrated_dfx,calibrated_dfs,nss_classic_dfx,"
         "nss_classic_dfs,exact_strips_dfx,exact_strips_dfs,nss_dfx,nss_dfs,nss_dmz,"
         "exact_strips_calibrated_dfx,exact_strips_calibrated_dfs,message\n";
  std::printf(
      "%-5s %5s %2s %6s %5s %8s %8s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | %6s %6s | "
      "%6s %6s | %6s %6s\n",
      "wheel", "y", "p", "method", "a/b", "Fx", "Fs", "ell.x", "ell.s", "str.x", "str.s", "frc.x",
      "frc.s", "cal.x", "cal.s", "nsc.x", "nsc.s", "exs.x", "exs.s", "nss.x", "nss.s");
  double worst[8][2] = {};
  for (const A22State& s : states) {
    const A22Wheel w = runA22Wheel(search, s, ao);
    if (!w.message.empty()) continue;
    for (const A22Patch& p : w.patches) {
      if (!(p.ours.fn > 0.0) || !p.exact.solved || p.ours.merged_into >= 0) continue;
      // The eta frame (toward the track centre) on both wheels: the left wheel's contact-frame
      // creepages mirrored (y -> -y: eta and phi change sign).
      const double mirror = s.side == WheelSide::kLeft ? -1.0 : 1.0;
      const Creepages c{p.creepages.xi, mirror * p.creepages.eta, mirror * p.creepages.phi};
      HalfspaceSolver solver(p.exact.grid, ao.G, ao.nu);
      solver.setPressure(p.exact.p);
      // The grid is centred at eta_offset: the spin's lever and the moment from the point.
      const double e = p.exact.eta_offset;
      const HalfspaceSolution& x =
          solver.solve(RollingMode::kSteady, Creepages{c.xi - c.phi * e, c.eta, c.phi}, o.mu);
      const Forces ex{x.fx, x.fy, x.mz - e * x.fx};
      const double scale = o.mu * p.exact.fn, a = p.ours.a, b = p.ours.b, fn = p.ours.fn;
      const PatchShape ours = patchShapeOf(p.ours);
      double ea = 0.0, eb = 0.0;
      const PatchShape exs = exactStrips(p.exact, &ea, &eb);
      std::string message;
      const Forces fe = steadyOn(nullptr, StripBound::kCommonCurvature,
                                 std::max(a, kKalkerMinAOverB * b), b, fn, c, o, ao.G, ao.nu);
      const Forces fs = steadyOn(&ours, StripBound::kCommonCurvature, a, b, fn, c, o, ao.G, ao.nu);
      const Forces ff = steadyOn(&ours, StripBound::kStripForce, a, b, fn, c, o, ao.G, ao.nu);
      const Forces fc = modelOn("steady", FastSimVariant::kCalibrated, ours, a, b, fn, c, o, ao.G,
                                ao.nu, 1, &message);
      const Forces fnss = modelOn("nss", FastSimVariant::kClassic, ours, a, b, fn, c, o, ao.G,
                                  ao.nu, 400, &message);
      const Forces fx =
          steadyOn(&exs, StripBound::kCommonCurvature, ea, eb, p.exact.fn, c, o, ao.G, ao.nu);
      // nss as it runs by default: the calibrated variant.
      const Forces fnc = modelOn("nss", FastSimVariant::kCalibrated, ours, a, b, fn, c, o, ao.G,
                                 ao.nu, 400, &message);
      const Forces fxc = modelOn("steady", FastSimVariant::kCalibrated, exs, ea, eb, p.exact.fn, c,
                                 o, ao.G, ao.nu, 1, &message);
      const Forces all[8] = {fe, fs, ff, fc, fnss, fx, fnc, fxc};
      double d[8][3];
      for (int k = 0; k < 8; ++k) {
        d[k][0] = (all[k].fx - ex.fx) / scale;
        d[k][1] = (all[k].fy - ex.fy) / scale;
        d[k][2] = (all[k].mz - ex.mz) / (scale * b);
        worst[k][0] = std::max(worst[k][0], std::abs(d[k][0]));
        worst[k][1] = std::max(worst[k][1], std::abs(d[k][1]));
      }
      const char* side = s.side == WheelSide::kLeft ? "left" : "right";
      const char* method = p.ours.method == NormalMethod::kHertz ? "hertz" : "strips";
      char row[1024];
      std::snprintf(
          row, sizeof row,
          "%s,%.1f,%d,%d,%s,%.3f,%.1f,%.1f,%.4g,%.4g,%.4g,%.1f,%.1f,%.3f,%.4f,%.4f,%.4f,"
          "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,\"%s\"\n",
          side, s.y_mm, p.index, int(p.candidate.zone), method, a / b, fn, p.exact.fn, c.xi, c.eta,
          c.phi, ex.fx, ex.fy, ex.mz, d[0][0], d[0][1], d[1][0], d[1][1], d[1][2], d[2][0], d[2][1],
          d[3][0], d[3][1], d[4][0], d[4][1], d[5][0], d[5][1], d[6][0], d[6][1], d[6][2], d[7][0],
          d[7][1], message.c_str());
      out << row;
      std::printf(
          "%-5s %5.1f %2d %6s %5.2f %8.0f %8.0f | %6.3f %6.3f | %6.3f %6.3f | %6.3f "
          "%6.3f | %6.3f %6.3f | %6.3f %6.3f | %6.3f %6.3f | %6.3f %6.3f\n",
          side, s.y_mm, p.index, method, a / b, ex.fx, ex.fy, d[0][0], d[0][1], d[1][0], d[1][1],
          d[2][0], d[2][1], d[3][0], d[3][1], d[4][0], d[4][1], d[5][0], d[5][1], d[6][0], d[6][1]);
      std::fflush(stdout);
    }
  }
  const char* names[8] = {"ellipse",     "strips",       "strip_force", "calibrated",
                          "nss_classic", "exact_strips", "nss",         "exact_strips_calibrated"};
  for (int k = 0; k < 8; ++k)
    std::printf("worst |dFx|, |dFs| over mu Fn: %-13s %.3f %.3f\n", names[k], worst[k][0],
                worst[k][1]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("true_patch_accuracy", argc, argv, addOptions, run);
}
