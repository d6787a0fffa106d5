// stability_map: where each creep-force model breaks down or stops being accurate (issue 6).
// For every model, a log grid of lambda/a (0.5..200) x V dt/dx (0.01..10; dx = 2a/nx, the element
// of the central strip, the simulator's step fixed by V and dt), four harmonic inputs in the
// rolled distance (theta = 2 pi q / lambda, V = 20 m/s, constant load unless said otherwise):
//   adhesion      xi = 1e-5 cos, eta = 1e-5 sin  linear: reference C_Kalker * C^exact/C^exact(inf)
//   partial-slip  xi = 3e-3 cos, eta = 3e-3 sin  |creepage| fixed, about 1/3 of saturation
//   full-slip     xi = 3e-2 cos, eta = 3e-2 sin  always saturated
//   spin          phi = 4 cos [1/m], eta = 1e-3 sin  spin-dominated partial slip
// A cell settles 8 a of travel from rest, then analyses a window of whole periods (>= 6 a and
// >= 64 steps; at most 20000 steps, part of a period for the longest waves at the smallest steps).
// Its output is fitted by harmonics of the input (the response of a stable, time-invariant scheme
// is periodic in theta); classes, first match wins:
//   nan           a non-finite output
//   refused       a step came back kRejected (a regime the model declines with a message)
//   blow-up       |F| above mu Fz, or the non-periodic residual grows across the window
//   oscillation   non-periodic residual (energy off the input's harmonics) above osc_tol; where
//                 undersampled, a per-step sign-alternating part above osc_tol
//   undersampled  fewer than 2 steps per wavelength: the input itself is aliased
//   inaccurate    error above tol: adhesion against the exact linear reference (relative RMS);
//                 slip and varying load against the same model at the smallest step, interpolated
//                 in the travel over the part both windows cover (RMS / mu Fz)
//   good
// Every FastSim row runs the variant its label names (fastsim: classic or calibrated, set
// explicitly: the parameters' default may change, the map's rows must not); --fastsim picks the
// variants (classic,calibrated by default; the calibrated one for steady, nss fixed and nss
// adaptive under varying load).
// Output: <out>/stability_map.csv (one row per model, input, lambda/a, V dt/dx).
// Options: stability_map --help.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tool_options.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

struct Options {
  std::string out = "doc/data";
  int nx = 20, lambdas = 10, ratios = 7, refGrid = 30, exactGrid = 12;
  bool noExact = false;
  std::vector<std::string> fastsims = {"classic", "calibrated"};
  double tol = 0.1, slipTol = 0.05, oscTol = 0.02;
};

struct InputCase {
  const char* name;
  double xi, eta, phi;  // amplitudes of xi cos, eta sin, phi cos
  bool linear;
};
const InputCase kCases[] = {{"adhesion", 1e-5, 1e-5, 0.0, true},
                            {"partial-slip", 3e-3, 3e-3, 0.0, false},
                            {"full-slip", 3e-2, 3e-2, 0.0, false},
                            {"spin", 0.0, 1e-3, 4.0, false}};

struct ModelSpec {
  std::string label;
  const char* model;
  const char* mesh;
  bool varyingLoad;     // Fz = Fz0 (1 + 0.25 sin theta): judged against its own smallest step
  std::string fastsim;  // classic | calibrated; empty for the exact model
};

constexpr double kV = 20.0;          // rolling speed [m/s]
constexpr double kSettle = 8.0;      // travel before the window [a]: e^-8/1.4 of chi3 a
constexpr double kMinWindow = 6.0;   // shortest window [a]
constexpr int kMinSamples = 64;      // shortest window [steps]
constexpr int kHarmonics = 16;       // harmonics of the input fitted
constexpr double kLoadSwing = 0.25;  // varying load amplitude [Fz0]
constexpr long kMaxWindow = 20000;   // longest window [steps]: part of a long wave

struct Window {
  std::vector<double> q, theta, fx, fy, fz;  // q: travel from the start [m]
  bool finite = true, refused = false;
  int notConverged = 0;
  double maxForceRatio = 0.0;  // max |F| / (mu Fz)
  std::string message;
};

StepInput inputAt(const InputCase& c, const ModelSpec& m, double theta, double dt, double fz0) {
  const double fz = fz0 * (m.varyingLoad ? 1.0 + kLoadSwing * std::sin(theta) : 1.0);
  return {dt, kV, c.xi * std::cos(theta), c.eta * std::sin(theta), c.phi * std::cos(theta), fz};
}

// One cell: settle, then record the window's outputs (stops at the first non-finite one).
Window simulate(const ModelSpec& m, const ContactParameters& p, const InputCase& c, double lOverA,
                double dq) {
  auto model = makeContactModel(p);
  const double dt = dq / kV, lambda = lOverA * p.a0;
  const double perStep = 2.0 * M_PI * dq / lambda, stepsPerPeriod = lambda / dq;
  const long settle = static_cast<long>(std::ceil(kSettle * p.a0 / dq));
  const long periods = std::max(1L, static_cast<long>(std::ceil(kMinWindow / lOverA)));
  const long window =
      std::min(kMaxWindow, std::max<long>(kMinSamples, std::ceil(periods * stepsPerPeriod - 1e-9)));
  Window w;
  for (long k = 0; k < settle + window; ++k) {
    const double theta = k * perStep;
    const StepInput in = inputAt(c, m, theta, k == 0 ? 0.0 : dt, p.fz0);
    const StepOutput o = model->step(in);
    if (!std::isfinite(o.fx) || !std::isfinite(o.fy) || !std::isfinite(o.mz)) {
      w.finite = false;
      return w;
    }
    if (o.status == StepStatus::kRejected && !w.refused) {
      w.refused = true;
      w.message = o.message;
    }
    w.notConverged += o.status == StepStatus::kNotConverged;
    w.maxForceRatio = std::max(w.maxForceRatio, std::hypot(o.fx, o.fy) / (p.mu * in.fz));
    if (k < settle) continue;
    w.q.push_back(k * dq);
    w.theta.push_back(std::remainder(theta, 2.0 * M_PI));
    w.fx.push_back(o.fx);
    w.fy.push_back(o.fy);
    w.fz.push_back(in.fz);
  }
  return w;
}

// Least-squares fit of a signal sampled at theta by 1, cos n theta, sin n theta (n <= H): the part
// of a stable scheme's response that is periodic at the input's period.
struct HarmonicFit {
  Eigen::VectorXd cx, cy;
  Eigen::MatrixXd basis(const std::vector<double>& theta) const {
    Eigen::MatrixXd B(theta.size(), 2 * kHarmonics + 1);
    for (size_t k = 0; k < theta.size(); ++k) {
      B(k, 0) = 1.0;
      for (int n = 1; n <= kHarmonics; ++n) {
        B(k, 2 * n - 1) = std::cos(n * theta[k]);
        B(k, 2 * n) = std::sin(n * theta[k]);
      }
    }
    return B;
  }
  explicit HarmonicFit(const Window& w) {
    const Eigen::MatrixXd B = basis(w.theta);
    const auto qr = B.colPivHouseholderQr();
    cx = qr.solve(Eigen::Map<const Eigen::VectorXd>(w.fx.data(), w.fx.size()));
    cy = qr.solve(Eigen::Map<const Eigen::VectorXd>(w.fy.data(), w.fy.size()));
  }
  HarmonicFit() = default;
};

struct Judgement {
  std::string cls;
  double error = 0.0, residual = 0.0, alternating = 0.0;
};

// RMS over the window of |(fx, fy) - (gx, gy)|.
double rmsDistance(const std::vector<double>& fx, const std::vector<double>& fy,
                   const Eigen::VectorXd& gx, const Eigen::VectorXd& gy, long from, long to) {
  double s = 0.0;
  for (long k = from; k < to; ++k) s += std::pow(fx[k] - gx(k), 2) + std::pow(fy[k] - gy(k), 2);
  return std::sqrt(s / std::max(1L, to - from));
}

// The exact linear reference in adhesion: F = -G a b Re(C e^{i theta}) per unit amplitude, with
// C = C_Kalker * C^exact(lambda)/C^exact(inf): the exact dynamics on Kalker's steady coefficient,
// the value FastSim's flexibilities are built from (the reference grid's own steady error cancels).
struct LinearReference {
  std::complex<double> cx, cy;  // for xi (cos) and eta (sin)
  void forces(const ContactParameters& p, const InputCase& c, const std::vector<double>& theta,
              Eigen::VectorXd* fx, Eigen::VectorXd* fy) const {
    const double gab = p.G * p.a0 * p.b0;
    fx->resize(theta.size());
    fy->resize(theta.size());
    for (size_t k = 0; k < theta.size(); ++k) {
      const std::complex<double> e = std::polar(1.0, theta[k]);
      (*fx)(k) = -gab * c.xi * (cx * e).real();
      (*fy)(k) = -gab * c.eta * (cy * std::complex<double>(0.0, -1.0) * e).real();
    }
  }
};

// The finest run at travel q, linear between its samples (uniform in q); false outside its window.
bool interpolate(const Window& f, double q, double* fx, double* fy) {
  if (f.q.size() < 2 || q < f.q.front() || q > f.q.back()) return false;
  const double dq = f.q[1] - f.q[0];
  const size_t i = std::min(f.q.size() - 2, static_cast<size_t>((q - f.q.front()) / dq));
  const double t = (q - f.q[i]) / dq;
  *fx = f.fx[i] + t * (f.fx[i + 1] - f.fx[i]);
  *fy = f.fy[i] + t * (f.fy[i + 1] - f.fy[i]);
  return true;
}

// RMS / scale of the run against the finest one, over the travel both windows cover.
double errorAgainstFine(const Window& w, const Window& fine, double scale) {
  double s = 0.0, fx, fy;
  long n = 0;
  for (size_t k = 0; k < w.q.size(); ++k)
    if (interpolate(fine, w.q[k], &fx, &fy)) {
      s += std::pow(w.fx[k] - fx, 2) + std::pow(w.fy[k] - fy, 2);
      ++n;
    }
  return n > 0 ? std::sqrt(s / n) / scale : 0.0;
}

Judgement judge(const Options& o, const ContactParameters& p, const InputCase& c, const Window& w,
                double stepsPerPeriod, const LinearReference* linear, const Window* fine) {
  Judgement j;
  if (!w.finite) return {"nan"};
  if (w.refused) return {"refused"};
  const HarmonicFit fit(w);
  const Eigen::MatrixXd B = fit.basis(w.theta);
  const Eigen::VectorXd gx = B * fit.cx, gy = B * fit.cy;
  const long n = static_cast<long>(w.theta.size());
  double scale = p.mu * p.fz0;
  if (linear) {
    Eigen::VectorXd rx, ry;
    linear->forces(p, c, w.theta, &rx, &ry);
    scale = std::sqrt((rx.squaredNorm() + ry.squaredNorm()) / n);
    j.error = rmsDistance(w.fx, w.fy, rx, ry, 0, n) / scale;
  } else {
    j.error = errorAgainstFine(w, *fine, scale);
  }
  j.residual = rmsDistance(w.fx, w.fy, gx, gy, 0, n) / scale;
  double alt = 0.0;  // the per-step sign-alternating part of what the fit leaves
  for (long k = 0; k < n; ++k) alt += (k % 2 ? -1.0 : 1.0) * (w.fx[k] - gx(k) + w.fy[k] - gy(k));
  j.alternating = std::abs(alt) / n / scale;
  const double early = rmsDistance(w.fx, w.fy, gx, gy, 0, n / 2);
  const double late = rmsDistance(w.fx, w.fy, gx, gy, n / 2, n);
  // Growth: what is not periodic doubles across the window and is large (a bounded scheme that
  // grows ends on a limit cycle, classed as oscillation below).
  if (w.maxForceRatio > 1.0 + 1e-6 || (late > 2.0 * early && late > 0.1 * scale))
    j.cls = "blow-up";
  else if (stepsPerPeriod < 2.0)  // the samples cannot show the input's period: only a step-to-step
    j.cls = j.alternating > o.oscTol ? "oscillation" : "undersampled";  // alternation counts
  else if (j.residual > o.oscTol)
    j.cls = "oscillation";
  else if (j.error > (linear ? o.tol : o.slipTol))
    j.cls = "inaccurate";
  else
    j.cls = "good";
  return j;
}

std::vector<double> logGrid(double lo, double hi, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(lo * std::pow(hi / lo, n > 1 ? i / (n - 1.0) : 0.0));
  return v;
}

struct Sweep {
  const Options& o;
  std::ofstream& csv;
  const NonSteadyCoefficients* exact[2];

  void model(const ModelSpec& m, const std::vector<double>& lambdas,
             const std::vector<double>& ratios, int meshN) {
    ContactParameters p;
    p.model = m.model;
    p.mesh = m.mesh;
    p.nx = p.ny = meshN;
    if (!m.fastsim.empty()) setParameter(&p, "fastsim", m.fastsim);  // the exact model: none
    if (m.varyingLoad) p.fz_max = p.fz0 * (1.0 + kLoadSwing);
    const CreepCoefficients kalker = kalkerCoefficients(p.a0 / p.b0, p.nu);
    const double c0 = kalker.c11, c1 = kalker.c22;
    for (const InputCase& c : kCases) {
      const auto t0 = std::chrono::steady_clock::now();
      for (double l : lambdas) {
        LinearReference ref{c0 * exact[0]->at(l) / exact[0]->steady(),
                            c1 * exact[1]->at(l) / exact[1]->steady()};
        const bool linear = c.linear && !m.varyingLoad;
        Window fine;  // the smallest step's run: reference of the slip cases
        for (size_t r = 0; r < ratios.size(); ++r) {
          // Steps per period with FastSim's dx = 2a/nx (the exact grid's own element differs).
          const double perPeriod = l * o.nx / (2.0 * ratios[r]);
          const Window w = simulate(m, p, c, l, ratios[r] * 2.0 * p.a0 / o.nx);
          if (r == 0) fine = w;
          const Judgement j = judge(o, p, c, w, perPeriod, linear ? &ref : nullptr, &fine);
          char line[320];
          std::snprintf(line, sizeof line, "%s,%s,%s,%.5g,%.5g,%.5g,%s,%.5g,%.5g,%.5g,%.6g,%d,%s\n",
                        m.label.c_str(), m.fastsim.empty() ? "-" : m.fastsim.c_str(), c.name, l,
                        ratios[r], perPeriod, j.cls.c_str(), j.error, j.residual, j.alternating,
                        w.maxForceRatio, w.notConverged,
                        linear ? "exact linear" : "own smallest step");
          csv << line;
        }
      }
      csv.flush();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << m.label << " " << c.name << ": " << s << " s\n";
    }
  }
};

bool runs(const Options& o, const std::string& fastsim) {
  return std::find(o.fastsims.begin(), o.fastsims.end(), fastsim) != o.fastsims.end();
}

void addOptions(CLI::App& app, Options* o) {
  app.description("Where each creep-force model breaks down or stops being accurate.");
  tools::option(app, "--out", &o->out, "output folder (must exist)");
  tools::option(app, "--nx", &o->nx, "FastSim mesh nx = ny");
  tools::option(app, "--lambdas", &o->lambdas, "wavelengths lambda/a in [0.5, 200], log-spaced");
  tools::option(app, "--ratios", &o->ratios, "steps V dt/dx in [0.01, 10], log-spaced");
  tools::option(app, "--ref-grid", &o->refGrid, "exact grid of the linear reference");
  tools::option(app, "--exact-grid", &o->exactGrid, "grid of the exact model's own rows");
  tools::flag(app, "--no-exact", &o->noExact, "leave the exact model's rows out");
  tools::option(app, "--tol", &o->tol, "adhesion: error above this is inaccurate");
  tools::option(app, "--slip-tol", &o->slipTol, "slip and varying load: likewise");
  tools::option(app, "--osc-tol", &o->oscTol, "non-periodic residual above this: oscillation");
  tools::option(app, "--fastsim", &o->fastsims, "the FastSim variants mapped",
                {"classic", "calibrated"});
}

int run(const Options& o) {
  tools::requireFolder(o.out);
  const ContactParameters p;
  const NonSteadyCoefficients x(CreepageKind::kXi, p.a0 / p.b0, p.nu, o.refGrid, o.refGrid);
  const NonSteadyCoefficients y(CreepageKind::kEta, p.a0 / p.b0, p.nu, o.refGrid, o.refGrid);
  std::ofstream csv = tools::writeFile(o.out + "/stability_map.csv");
  csv << "model,fastsim,input,lambda_over_a,step_over_dx,steps_per_period,class,error,residual,"
         "alternating,max_force_ratio,not_converged,reference\n";
  Sweep sweep{o, csv, {&x, &y}};
  const auto lambdas = logGrid(0.5, 200.0, o.lambdas), ratios = logGrid(0.01, 10.0, o.ratios);
  // Classic and calibrated of one model side by side; shen-li in classic only.
  const ModelSpec fastsim[] = {
      {"steady", "steady", "fixed", false, "classic"},
      {"steady", "steady", "fixed", false, "calibrated"},
      {"shen-li", "shen-li", "fixed", false, "classic"},
      {"nss fixed", "nss", "fixed", false, "classic"},
      {"nss fixed", "nss", "fixed", false, "calibrated"},
      {"nss adaptive + varying load", "nss", "adaptive", true, "classic"},
      {"nss adaptive + varying load", "nss", "adaptive", true, "calibrated"}};
  for (ModelSpec m : fastsim) {
    if (!runs(o, m.fastsim)) continue;
    m.label += " (" + m.fastsim + ")";
    sweep.model(m, lambdas, ratios, o.nx);
  }
  if (!o.noExact) {
    // Every other wavelength; steps no shorter than the exact grid's element (2.2 a / grid), as
    // the exact model holds its output between its one-element sub-steps.
    std::vector<double> el, er;
    for (size_t i = 0; i < lambdas.size(); i += 2) el.push_back(lambdas[i]);
    er.push_back(2.2 / o.exactGrid * o.nx / 2.0);  // one sub-step per step: its own scheme
    for (double r : ratios)
      if (r > er.front() * (1 + 1e-9)) er.push_back(r);
    sweep.model({"exact", "exact", "fixed", false, ""}, el, er, o.exactGrid);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return tools::runMain<Options>("stability_map", argc, argv, addOptions, run);
}
