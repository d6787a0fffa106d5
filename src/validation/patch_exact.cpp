#include "validation/patch_exact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

/// The gap beyond g(0) (what = 0) by Catmull-Rom between the samples, or cos(delta) / (2 r)
/// (what = 1) linearly. The gap must be smooth: a linear one has kinks at the samples, lines of
/// concentrated curvature that the exact solver answers with pressure ripples of some 10 % of the
/// peak at sample spacings of 0.5 mm.
double interp(const ContactCandidate& c, double e, int what) {
  const auto& f = c.gap_function;
  const std::size_t n = f.size();
  std::size_t i = 0;
  while (i + 2 < n && f[i + 1].eta < e) ++i;
  const double t = std::clamp((e - f[i].eta) / (f[i + 1].eta - f[i].eta), 0.0, 1.0);
  if (what == 1) {
    auto v = [&](const GapSample& s) {
      return std::cos(s.contact_angle) / (2.0 * s.rolling_radius);
    };
    return v(f[i]) + t * (v(f[i + 1]) - v(f[i]));
  }
  const double p1 = f[i].gap, p2 = f[i + 1].gap;
  const double p0 = i > 0 ? f[i - 1].gap : 2.0 * p1 - p2;  // equal spacing; linear beyond the ends
  const double p3 = i + 2 < n ? f[i + 2].gap : 2.0 * p2 - p1;
  const double v =
      p1 +
      0.5 * t *
          (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
  return v - c.gap;
}

}  // namespace

ExactPatch exactPatchNormal(const ContactCandidate& c, double approach, double G, double nu, int mx,
                            int my) {
  ExactPatch e;
  if (c.gap_function.size() < 2) return e;
  double lo = 1e9, hi = -1e9, xmax = 0.0;
  for (const GapSample& s : c.gap_function) {
    const double pen = approach - (s.gap - c.gap);
    if (pen <= 0.0) continue;
    lo = std::min(lo, s.eta);
    hi = std::max(hi, s.eta);
    xmax = std::max(xmax, std::sqrt(pen / interp(c, s.eta, 1)));
  }
  if (!(hi >= lo)) return e;
  const double de = c.gap_function[1].eta - c.gap_function[0].eta;
  lo -= de;  // the interpenetration reaches at most one sample beyond the last inside
  hi += de;
  e.grid.mx = mx;
  e.grid.my = my;
  e.grid.dx = 2.0 * 1.02 * xmax / mx;
  e.grid.dy = (hi - lo) / my;
  e.eta_offset = 0.5 * (lo + hi);
  Eigen::VectorXd h(e.grid.size());
  for (int ix = 0; ix < mx; ++ix)
    for (int iy = 0; iy < my; ++iy) {
      const double x = e.grid.xc(ix), eta = e.eta_offset + e.grid.yc(iy);
      h[e.grid.index(ix, iy)] = interp(c, eta, 0) + interp(c, eta, 1) * x * x;
    }
  e.solution = solveNormalGapApproach(e.grid, G, nu, h, approach);
  e.fn = e.solution.fz;
  e.pmax = e.solution.p.maxCoeff();
  e.eta_min = 1e9;
  e.eta_max = -1e9;
  for (int ix = 0; ix < mx; ++ix)
    for (int iy = 0; iy < my; ++iy)
      if (e.solution.p[e.grid.index(ix, iy)] > 0.0) {
        e.eta_min = std::min(e.eta_min, e.eta_offset + e.grid.yc(iy) - 0.5 * e.grid.dy);
        e.eta_max = std::max(e.eta_max, e.eta_offset + e.grid.yc(iy) + 0.5 * e.grid.dy);
      }
  return e;
}

std::vector<double> exactWheelLoad(const WheelContactGeometry& geo, double load, double G,
                                   double nu, int m, double guess) {
  std::vector<double> fn;
  auto residual = [&](double dv) {
    double fz = 0.0;
    fn.assign(geo.candidates.size(), 0.0);
    for (std::size_t i = 0; i < geo.candidates.size(); ++i) {
      const ContactCandidate& c = geo.candidates[i];
      const double d = dv * c.normal.y() - c.gap;
      if (d <= 0.0) continue;
      fn[i] = exactPatchNormal(c, d, G, nu, m, m).fn;
      fz += fn[i] * c.normal.y();
    }
    return std::cbrt(fz * fz) - std::cbrt(load * load);  // nearly linear in dv
  };
  double d0 = guess, d1 = 1.02 * guess;
  double r0 = residual(d0), r1 = residual(d1);
  for (int it = 0; it < 20 && std::abs(r1) > 1e-6 * std::cbrt(load * load) && r1 != r0; ++it) {
    const double d2 = d1 - r1 * (d1 - d0) / (r1 - r0);
    d0 = d1;
    r0 = r1;
    d1 = d2;
    r1 = residual(d1);
  }
  return fn;
}

ExactPatchTangential::ExactPatchTangential(const ExactPatch& patch, WheelSide side, double G,
                                           double nu, double fn, SolverControl control) {
  const HalfspaceGrid& g = patch.grid;
  if (g.size() == 0 || patch.solution.p.size() != g.size() || !(patch.fn > 0.0))
    throw std::invalid_argument("exact tangential: the patch carries no load");
  const bool left = side == WheelSide::kLeft;
  // The left wheel's contact y is -eta: its pressure mirrored across the grid's rows.
  Eigen::VectorXd p(g.size());
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy)
      p[g.index(ix, left ? g.my - 1 - iy : iy)] = patch.solution.p[g.index(ix, iy)];
  if (fn > 0.0) p *= fn / patch.fn;
  y0_ = left ? -patch.eta_offset : patch.eta_offset;
  solver_ = std::make_unique<HalfspaceSolver>(g, G, nu, control);
  solver_->setPressure(p);
}

ExactTangential ExactPatchTangential::solve(RollingMode mode, const Creepages& w, double mu) {
  const HalfspaceSolution& s = solver_->solve(mode, {w.xi - w.phi * y0_, w.eta, w.phi}, mu);
  ExactTangential t;
  t.fx = s.fx;
  t.fs = s.fy;
  t.mz = s.mz - y0_ * s.fx;
  t.adhesion_fraction = s.adhesionFraction;
  t.converged = s.converged;
  t.iterations = s.iterations;
  return t;
}

ExactTangential ExactPatchTangential::steady(const Creepages& w, double mu) {
  return solve(RollingMode::kSteady, w, mu);
}

ExactTangential ExactPatchTangential::step(const Creepages& w, double mu) {
  return solve(RollingMode::kTransient, w, mu);
}

void ExactPatchTangential::clearHistory() {
  solver_->clearHistory();
}

double ExactPatchTangential::dx() const {
  return solver_->grid().dx;
}

ExactTangential exactPatchTangential(const ExactPatch& patch, WheelSide side, double G, double nu,
                                     const Creepages& w, double mu, double fn) {
  return ExactPatchTangential(patch, side, G, nu, fn).steady(w, mu);
}

}  // namespace wheel_rail_contact
