#include "core/models/auto_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/fastsim/fastsim.hpp"
#include "core/models/steady_model.hpp"
#include "core/models/step_geometry.hpp"
#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

namespace wheel_rail_contact {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The shares come from the chart (doc/data/speed_accuracy_scenes.csv). On the frequency sweep
// the estimate is steady FastSim's error beyond nss's or somewhat above it, and FastSim's own error
// stays well below the tolerance on long waves on every mesh (doc/performance.md#model-auto). So
// NSS-FastSim starts above 0.85 of the tolerance, leaving the rest to FastSim's own error, and
// hands back below 0.8 once the patch has rolled kCalmTransits lengths 2a in calm, so its history
// has flushed through the patch.
constexpr double kStartShare = 0.85;
constexpr double kReturnShare = 0.8;
constexpr double kCalmTransits = 2.0;
// On the chart's varying-load scenes steady FastSim's error beyond nss's is at most 0.3 of the
// lag estimate l |dfz/dq| / fz / sqrt 2 (0.02-0.3 over the twelve scenes, 5x5 and 20x20; 0.08-0.3
// with the calibrated FastSim): the patch's size follows the load at once, only the traction's
// shape lags. The shares and this weight hold for both variants: the sweep is linear, where the
// calibration's ratios are 1, and so is the relaxation length.
constexpr double kLoadWeight = 0.3;
// The share of the tolerance the equivalent ellipse's predicted departure (ellipseDeparture, over
// the force) may take before the patch's strips are run, and the share it must fall below over a
// whole window before the ellipse is run again. On A-2.2's patches the departure FastSim shows
// is at most the prediction plus 0.005 of the force (test_auto_patch_shape.cpp), so the ellipse
// stays within 0.5 tolerance + 0.005 of the strips, leaving the rest to FastSim's own error.
constexpr double kStripsShare = 0.5;
constexpr double kEllipseShare = 0.4;

// The peaks are held over the longest wavelength that still needs NSS-FastSim
// (2 pi l / (kStartShare tolerance)), so a harmonic input keeps one estimate over its whole period.
double peakWindow(double l, double tolerance) {
  return 2.0 * kPi * l / (kStartShare * tolerance);
}

// The distance each hand-over phase (calm, then blend) lasts on a patch of semi-axis a [m].
double calmDistance(double a) {
  return kCalmTransits * 2.0 * a;
}

ContactParameters withMesh(ContactParameters p, int n, const char* model) {
  p.nx = p.ny = n;
  p.model = model;
  return p;
}

}  // namespace

SteadinessMonitor::SteadinessMonitor(double l, double window, const CreepCoefficients& c,
                                     double sqrtAb, double nu)
    : l_(l), bucket_(0.5 * window), sqrtAb_(sqrtAb), nu_(nu), c_(c) {}

void SteadinessMonitor::reset() {
  primed_ = false;
  travelled_ = estimate_ = 0.0;
  held_ = current_ = Peaks{};
}

double SteadinessMonitor::update(const StepInput& in) {
  const double dq = std::abs(in.V) * in.dt;
  // Linear-theory force in the contact frame: creepages are per signed V, so a reversal at
  // constant creepage turns xi's and eta's forces over (rolling_direction.hpp) and must count.
  const double dir = in.V < 0.0 ? -1.0 : 1.0;
  double fx = dir * c_.c11 * in.xi, fy = dir * c_.c22 * in.eta + c_.c23 * in.phi * sqrtAb_;
  if (in.a != 0.0) {
    // The step's own patch: the force of the creepages at its a/b and area (per G a0 b0), so a
    // changing geometry counts as a changing input.
    const CreepCoefficients c = kalkerCoefficients(stepAOverB(in, 1.0), nu_);  // a shape's held
    const double area = in.a * in.b / (sqrtAb_ * sqrtAb_);
    fx = area * dir * c.c11 * in.xi;
    fy = area * (dir * c.c22 * in.eta + c.c23 * in.phi * std::sqrt(in.a * in.b));
  }
  if (primed_) {
    travelled_ += dq;
    if (travelled_ > bucket_) {  // two buckets: the peaks of the last half to whole window
      held_ = current_;
      current_ = Peaks{};
      travelled_ = 0.0;
    }
    const double dfx = fx - fx_, dfy = fy - fy_;
    current_.slope = std::max(current_.slope, std::sqrt(dfx * dfx + dfy * dfy) / dq);
    current_.load = std::max(current_.load, std::abs(in.fz - fz_) / (in.fz * dq));
  }
  current_.size = std::max(current_.size, std::sqrt(fx * fx + fy * fy));
  fx_ = fx;
  fy_ = fy;
  fz_ = in.fz;
  primed_ = true;
  const double slope = std::max(held_.slope, current_.slope),
               size = std::max(held_.size, current_.size),
               load = std::max(held_.load, current_.load);
  // The error measure is an RMS over a period against the peak: a harmonic's is its peak / sqrt 2.
  estimate_ = l_ * std::max(size > 0.0 ? slope / size : 0.0, kLoadWeight * load) / std::sqrt(2.0);
  return estimate_;
}

namespace {

// The simplified theory's saturation of a linear-theory force (fx, fy) at capacity mu fz.
void saturate(double cap, double* fx, double* fy) {
  const double f = std::hypot(*fx, *fy);
  if (!(f > 0.0) || !(cap > 0.0)) return;
  const double s = f / cap, g = s < 3.0 ? s * (1.0 - s / 3.0 + s * s / 27.0) : 1.0;
  *fx *= cap * g / f;
  *fy *= cap * g / f;
}

}  // namespace

ShapeDeparture ellipseDeparture(const StepInput& in, double G, double nu, double mu) {
  ShapeDeparture d;
  if (!in.shape || !(in.a > 0.0) || !(in.b > 0.0)) return d;
  const double a = in.a, b = in.b;
  const Flexibilities L = kalkerFlexibilities(a, b, G, kalkerCoefficients(stepAOverB(in, 1.0), nu));
  double s2 = 0.0, s2y = 0.0, s3 = 0.0;
  for (const PatchStrip& st : in.shape->strips) {
    if (!inContact(st)) continue;
    const double h = 0.5 * (st.x_lead - st.x_trail), wh2 = 2.0 * st.width * h * h;
    s2 += wh2;
    s2y += wh2 * st.eta;
    s3 += wh2 * h / 3.0;
  }
  if (!(s2 > 0.0)) return d;
  d.centre = s2y / s2;
  const double e2 = 8.0 * a * a * b / 3.0, e3 = kPi * a * a * a * b / 4.0;
  double sx = -(in.xi * s2 / L.L1 - in.phi * s2y / L.L3),
         sy = -(in.eta * s2 / L.L2 + in.phi * s3 / L.L3);
  double ex = -(in.xi - in.phi * d.centre) * e2 / L.L1,
         ey = -(in.eta * e2 / L.L2 + in.phi * e3 / L.L3);
  const double cap = mu * in.fz;
  saturate(cap, &sx, &sy);
  saturate(cap, &ex, &ey);
  d.difference = std::hypot(ex - sx, ey - sy);
  d.force = std::hypot(sx, sy);
  return d;
}

void PatchShapeMonitor::reset() {
  travelled_ = estimate_ = 0.0;
  held_ = current_ = Peaks{};
}

double PatchShapeMonitor::update(const ShapeDeparture& d, double dq) {
  travelled_ += dq;
  if (travelled_ > bucket_) {  // two buckets: the peaks of the last half to whole window
    held_ = current_;
    current_ = Peaks{};
    travelled_ = 0.0;
  }
  current_.difference = std::max(current_.difference, d.difference);
  current_.force = std::max(current_.force, d.force);
  const double difference = std::max(held_.difference, current_.difference),
               force = std::max(held_.force, current_.force);
  // No force at all (no creepage): no error either way, unless the shapes differ where the
  // creepage is zero, which they cannot in linear theory.
  estimate_ = force > 0.0 ? difference / force : 0.0;
  return estimate_;
}

namespace {

// From doc/data/speed_accuracy_reading.txt (scripts/speed_accuracy.sh, "auto's rule read off the
// chart"): worst error of nss on the adaptive n x n mesh, in the variant auto runs, over the
// combined and varying-load scenes and the frequency sweep from lambda/a = 10; each rung starts
// about 8 % above it. Finer meshes than the last rung gain nothing there: the model's own error
// dominates, and the last rung's mesh is also taken below its reach (shorter waves).
struct Rung {
  int n;
  double from;  // smallest tolerance for this mesh
};
// Classic: 5: 0.060, 10: 0.041, 20 to 40: 0.044 (each mesh with its own chi; 0.084, 0.046, 0.044
// with the 20x20 chi on every mesh); 10x10 reaches furthest, 20x20 is taken below 0.045.
constexpr Rung kClassicLadder[] = {{5, 0.064}, {10, 0.045}, {20, 0.0}};
constexpr double kClassicReach = 0.041;
// Calibrated (each mesh with its own steady table and the calibrated time-term filters): 5: 0.043,
// 10: 0.040, 20: 0.030, 30: 0.026, 40: 0.025, all load_xi0.002_l5; 20x20 is the finest rung and
// reaches furthest of the three.
constexpr Rung kCalibratedLadder[] = {{5, 0.047}, {10, 0.043}, {20, 0.0}};
constexpr double kCalibratedReach = 0.032;

}  // namespace

int meshForTolerance(double tolerance, bool calibrated) {
  for (const Rung& r : calibrated ? kCalibratedLadder : kClassicLadder)
    if (tolerance >= r.from) return r.n;
  return 20;
}

double nssReachOnTheChart(bool calibrated) {
  return calibrated ? kCalibratedReach : kClassicReach;
}

double nssRelaxationLength(const ContactParameters& p, const ChiTable& chi) {
  const double ab = p.a0 / p.b0, lambdaOverA = 50.0;
  double worst = 0.0;
  const ChiTable at10 = chi.forMesh(10);
  for (const CreepageKind k : kCreepageKinds) {
    const std::complex<double> c =
        fastsimSecondOrderCoefficient(k, ab, p.nu, 10, 10, at10.secondOrderAt(k, ab), lambdaOverA);
    worst = std::max(worst, std::abs(1.0 - c / fastsimSteadyCoefficient(k, ab, p.nu, 10, 10)));
  }
  // A first-order lag 1 / (1 + i 2 pi l / lambda) errs by about 2 pi l / lambda.
  return worst * lambdaOverA * p.a0 / (2.0 * kPi);
}

AutoModel::AutoModel(const ContactParameters& p, const ChiTable& chi,
                     const CalibrationTable& calibration)
    : p_(p),
      calibrated_(!calibration.empty()),
      n_(meshForTolerance(p.tolerance, calibrated_)),
      l_(nssRelaxationLength(p, chi)),
      nss_(withMesh(p, n_, "nss"), chi, calibration),
      monitor_(l_, peakWindow(l_, p.tolerance), kalkerCoefficients(p.a0 / p.b0, p.nu),
               std::sqrt(p.a0 * p.b0), p.nu),
      shapeMonitor_(peakWindow(l_, p.tolerance)) {}

void AutoModel::reset() {
  nss_.reset();
  monitor_.reset();
  mode_ = Mode::kSteady;
  calm_ = handed_ = 0.0;
  shapeMonitor_.reset();
  strips_ = false;
}

std::string AutoModel::name() const {
  return mode_ == Mode::kSteady ? "auto:steady" : mode_ == Mode::kNss ? "auto:nss" : "auto:blend";
}

std::string AutoModel::choices() const {
  char reach[120] = "";
  const double best = nssReachOnTheChart(calibrated_);
  if (p_.tolerance < best)
    std::snprintf(reach, sizeof reach, " (below what NSS-FastSim reaches on the chart, %g)", best);
  char text[480];
  std::snprintf(text, sizeof text,
                "%s FastSim; mesh %dx%d for tolerance %g%s; relaxation length %.3g m; NSS-FastSim "
                "above an estimated steady error of %g; a non-Hertzian patch's strips above a "
                "predicted departure of its equivalent ellipse of %g",
                calibrated_ ? "calibrated" : "classic", n_, n_, p_.tolerance, reach, l_,
                kStartShare * p_.tolerance, kStripsShare * p_.tolerance);
  return text;
}

void AutoModel::choose(const StepInput& in) {
  const bool moving = !*checkStepInput(in) && in.V != 0.0 && in.dt > 0.0;
  if (!moving) return;
  if (!(in.fz > 0.0)) {
    monitor_.reset();  // contact lost: the next contact starts a new record
    return;
  }
  const double e = monitor_.update(in), dq = std::abs(in.V) * in.dt,
               calm = calmDistance(nss_.mesh().a());
  if (e > kStartShare * p_.tolerance) {
    mode_ = Mode::kNss;
    calm_ = 0.0;
  } else if (mode_ == Mode::kNss) {
    // Hand back only once the history has flushed through the patch in calm.
    calm_ = e < kReturnShare * p_.tolerance ? calm_ + dq : 0.0;
    if (calm_ > calm) {
      mode_ = Mode::kHandBack;
      handed_ = 0.0;
    }
  } else if (mode_ == Mode::kHandBack) {
    handed_ += dq;
    if (handed_ >= calm) mode_ = Mode::kSteady;
  }
}

StepOutput AutoModel::handBack(const StepInput& in) {
  StepOutput out = nss_.step(in);
  if (out.status != StepStatus::kOk) return out;
  // NSS-FastSim's lag error is small here but not zero: fade it out instead of dropping it.
  const StepOutput st = nss_.steadyAlongside(in);
  const double w = 1.0 - handed_ / calmDistance(nss_.mesh().a());
  out.fx = w * out.fx + (1.0 - w) * st.fx;
  out.fy = w * out.fy + (1.0 - w) * st.fy;
  out.mz = w * out.mz + (1.0 - w) * st.mz;
  out.adhesionFraction = w * out.adhesionFraction + (1.0 - w) * st.adhesionFraction;
  return out;
}

StepInput AutoModel::chooseGeometry(const StepInput& in) {
  centre_ = 0.0;
  if (!in.shape || *checkStepInput(in)) {
    // No shape (the ellipse is the patch), or a step the model refuses as given.
    if (!in.shape) {
      shapeMonitor_.reset();
      strips_ = false;
    }
    return in;
  }
  // Beyond Kalker's table only the strips can run the patch.
  if (aOverBHeld(in)) {
    strips_ = true;
    return in;
  }
  const double dq = std::abs(in.V) * in.dt;
  const ShapeDeparture d = ellipseDeparture(in, p_.G, p_.nu, stepMu(in, p_.mu));
  const double e = shapeMonitor_.update(d, dq);
  if (e > kStripsShare * p_.tolerance)
    strips_ = true;
  else if (e < kEllipseShare * p_.tolerance)
    strips_ = false;
  StepInput run = in;
  if (!strips_) {
    // The ellipse at the strips' centre: the rigid slip there is xi - phi y_c.
    run.shape = nullptr;
    centre_ = d.centre;
    run.xi = in.xi - in.phi * centre_;
  }
  return run;
}

StepOutput AutoModel::aboutReference(StepOutput out) const {
  // mz = x fy - y fx: from the ellipse's centre to the reference point (only then: a step without
  // a shape is left as it was, bit for bit).
  if (centre_ != 0.0) out.mz -= centre_ * out.fx;
  return out;
}

StepOutput AutoModel::step(const StepInput& given) {
  const StepInput in = chooseGeometry(given);
  // The time term's monitor sees the creepages as given: the ellipse's own, at its centre, move
  // with the choice, not with the input.
  choose(given);
  switch (mode_) {
    case Mode::kNss:
      return aboutReference(nss_.step(in));
    case Mode::kHandBack:
      return aboutReference(handBack(in));
    case Mode::kSteady:
      break;
  }
  return aboutReference(nss_.steadyStep(in));
}

}  // namespace wheel_rail_contact
