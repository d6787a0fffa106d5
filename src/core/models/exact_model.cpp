#include "core/models/exact_model.hpp"

#include <cmath>
#include <stdexcept>

#include "core/exact/halfspace_normal.hpp"
#include "core/models/rolling_direction.hpp"
#include "core/models/step_geometry.hpp"

namespace wheel_rail_contact {

namespace {

HalfspaceGrid gridFor(const ContactParameters& p) {
  validate(p);
  if (p.mesh != "fixed")
    throw std::invalid_argument("mesh: the exact model uses one fixed grid (mesh = fixed)");
  if (p.nx * p.ny > 3600)  // dense matrices over the loaded elements: about 180 MB at 60 x 60
    throw std::invalid_argument("nx: the exact model supports at most nx * ny = 3600 elements");
  const double s = std::cbrt(effectiveFzMax(p) / p.fz0);
  return HalfspaceGrid::covering(p.a0 * s, p.b0 * s, p.nx, p.ny);
}

StepInput lerp(const StepInput& a, const StepInput& b, double f, const ReferencePatch& ref,
               double mu) {
  StepInput r;
  r.V = a.V + f * (b.V - a.V);
  r.xi = a.xi + f * (b.xi - a.xi);
  r.eta = a.eta + f * (b.eta - a.eta);
  r.phi = a.phi + f * (b.phi - a.phi);
  r.fz = a.fz + f * (b.fz - a.fz);
  // Per-step geometry or friction at either end: both ends' own values (the parameters' where
  // absent) interpolated too.
  if (a.a != 0.0 || b.a != 0.0) {
    const HertzEllipse ha = stepPatch(a, ref), hb = stepPatch(b, ref);
    r.a = ha.a + f * (hb.a - ha.a);
    r.b = ha.b + f * (hb.b - ha.b);
  }
  if (a.mu != 0.0 || b.mu != 0.0) {
    const double ma = stepMu(a, mu), mb = stepMu(b, mu);
    r.mu = ma + f * (mb - ma);
  }
  return r;
}

}  // namespace

ExactModel::ExactModel(const ContactParameters& p)
    : p_(p),
      ref_{p.a0, p.b0, p.fz0},
      solver_(gridFor(p), p.G, p.nu),
      fzMax_(effectiveFzMax(p)),
      maxPatch_(ref_.at(fzMax_)) {}

void ExactModel::reset() {
  solver_.clearHistory();
  started_ = false;
  frame_.reset();
  carry_ = 0.0;
  subSteps_ = 0;
  last_ = StepOutput();
  // The next normal solve at this load must not reuse the old one scaled (up to 0.5 % off): a
  // fresh model solves anew (found by fuzzing: 7e-5 of fy after reset).
  loadedFz_ = -1.0;
}

void ExactModel::subStep(const StepInput& in) {
  // The normal problem is solved again when the load has moved by more than 0.5 % (a, b by
  // 0.17 %, a small fraction of an element on any grid this model allows); in between, its
  // pressure is scaled to the load, which keeps sum p dA = fz exactly.
  // A step's own a, b: solved again when either has moved by more than that 0.17 % too.
  const bool moved = in.a != 0.0 && (std::abs(in.a - loadedA_) > 1.7e-3 * loadedA_ ||
                                     std::abs(in.b - loadedB_) > 1.7e-3 * loadedB_);
  if (!(loadedFz_ > 0.0) || std::abs(in.fz - loadedFz_) > 5e-3 * loadedFz_ || moved) {
    const HertzEllipse h = stepPatch(in, ref_);
    normalPressure_ = hertzianGridPressure(solver_.grid(), h.a, h.b, in.fz, p_.G, p_.nu);
    loadedFz_ = in.fz;
    loadedA_ = h.a;
    loadedB_ = h.b;
  }
  solver_.setPressure(normalPressure_ * (in.fz / loadedFz_));
  // The slip solve squares the rigid slip: a subnormal creepage made it NaN (found by fuzzing).
  // Below 1e-100 a creepage is zero (its force would be below 1e-80 N).
  const auto flush = [](double c) { return std::abs(c) < 1e-100 ? 0.0 : c; };
  solver_.solve(RollingMode::kTransient, {flush(in.xi), flush(in.eta), flush(in.phi)},
                stepMu(in, p_.mu));
  ++subSteps_;
}

StepOutput ExactModel::contactFrame(StepOutput out) const {
  frame_.toContact(&out);
  return out;
}

StepOutput ExactModel::step(const StepInput& withShape) {
  StepOutput out;
  subSteps_ = 0;
  // A shape's patch is solved on its equivalent ellipse (the true patch's exact solution is the
  // validation's, not a model's), a/b within Kalker's range as for any per-step ellipse; the
  // pointer is not kept.
  StepInput given = withShape;
  given.shape = nullptr;
  if (screenStep(withShape, &out)) {
    if (out.status == StepStatus::kNoLoad) {
      reset();
      last_ = out;
    }
    return out;
  }
  if (withShape.shape && *checkStepInput(given)) {  // the ellipse's a/b beyond Kalker's table
    out.status = StepStatus::kRejected;
    out.message = checkStepInput(given);
    return out;
  }
  if (given.a == 0.0 && given.fz > fzMax_ * (1.0 + 1e-12)) {
    out.status = StepStatus::kRejected;
    out.message = "fz above fz_max: the fixed grid does not cover the patch";
    return out;
  }
  if (given.a != 0.0 &&
      (given.a > maxPatch_.a * (1.0 + 1e-12) || given.b > maxPatch_.b * (1.0 + 1e-12))) {
    out.status = StepStatus::kRejected;
    out.message =
        "exact model: the step's a or b exceeds the fixed grid's patch (a0, b0 at fz_max)";
    return out;
  }
  // Rolls forwards, in the mirror while V < 0. At a reversal, as the FastSim models: the traction
  // standing in the material is carried into the other direction's frame. The previous input
  // (what the sub-steps interpolate from) is re-expressed there with V = 0, the speed passing
  // through zero within this step; the remainder below one element restarts (at most one element
  // of travel).
  const StepInput in = frame_.face(given, [this] {
    solver_.mirrorHistoryAlongX();
    prev_ = mirroredInput(prev_);
    prev_.V = 0.0;
    carry_ = 0.0;
  });
  if (in.V == 0.0 && started_) {
    prev_ = in;  // the next step's travel starts from rest
    out = last_;
    out.status = StepStatus::kStandstill;
    out.message = "V = 0: no travel, forces held";
    return contactFrame(out);
  }
  const HertzEllipse h = stepPatch(in, ref_);
  if (!started_) {  // from rest: no distance rolled yet, no traction
    solver_.clearHistory();
    started_ = true;
    carry_ = 0.0;
    last_ = StepOutput();
    last_.adhesionFraction = 1.0;
  } else {
    const double dx = solver_.grid().dx;
    const double travel = 0.5 * (prev_.V + in.V) * in.dt;
    const double total = carry_ + travel;
    const double elements = std::floor(total / dx);
    const long cap = 10L * solver_.grid().mx;
    // Compared in double first: a long travel (e.g. 1e12 m) would overflow the cast to long (UB).
    // Clamped, sub-step k stands for element k + skip of the travel.
    const long n = elements > 2.0 * cap ? 2 * cap : static_cast<long>(elements);
    const double skip = elements - static_cast<double>(n);
    long first = 1;
    if (n > cap) {
      first = n - cap + 1;
      solver_.clearHistory();
    }
    for (long k = first; k <= n; ++k)  // the last one takes the row's own input
      subStep(k == n ? in : lerp(prev_, in, ((k + skip) * dx - carry_) / travel, ref_, p_.mu));
    // After a clamped (restarted) travel the remainder's rounding exceeds dx: start on a node.
    carry_ = elements > 2.0 * cap ? 0.0 : total - n * dx;
    if (n > 0) {
      const HalfspaceSolution& s = solver_.solution();
      last_.fx = s.fx;
      last_.fy = s.fy;
      last_.mz = s.mz;
      last_.adhesionFraction = s.adhesionFraction;
      last_.status = s.converged ? StepStatus::kOk : StepStatus::kNotConverged;
      last_.message = s.converged ? "" : "Gauss-Seidel hit its iteration cap";
    }
  }
  prev_ = in;
  out.fx = last_.fx;
  out.fy = last_.fy;
  out.mz = last_.mz;
  out.adhesionFraction = last_.adhesionFraction;
  out.status = last_.status;
  out.message = last_.message;
  out.fz = in.fz;
  out.a = h.a;
  out.b = h.b;
  last_ = out;  // in the march's frame
  if (withShape.shape && out.status == StepStatus::kOk && !*out.message)
    out.message = "exact model: solved on the shape's equivalent ellipse a, b";
  if (in.V == 0.0) {  // the first step at rest
    out.status = StepStatus::kStandstill;
    out.message = "V = 0: no travel, forces held";
  }
  return contactFrame(out);
}

}  // namespace wheel_rail_contact
