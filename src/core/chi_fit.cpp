#include "wheel_rail_contact/chi_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "wheel_rail_contact/fastsim_frequency.hpp"

namespace wheel_rail_contact {

ChiFit evaluateChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                   const ChiParameters& chi, const std::vector<FrequencyPoint>& exact) {
  ChiFit fit;
  fit.chi = chi;
  const double steady = fastsimSteadyCoefficient(kind, a_over_b, nu, nx, ny);
  std::vector<double> err(exact.size());
  for (size_t q = 0; q < exact.size(); ++q) {
    const auto c =
        fastsimNonSteadyCoefficient(kind, a_over_b, nu, nx, ny, chi, exact[q].lambdaOverA);
    err[q] = std::abs(c / steady - exact[q].ratio);
    if (exact[q].lambdaOverA >= 2.0) fit.maxError = std::max(fit.maxError, err[q]);
  }
  for (size_t q = 1; q < exact.size(); ++q) {  // trapezoids
    const double l0 = exact[q - 1].lambdaOverA, l1 = exact[q].lambdaOverA;
    fit.meanErrorLog += 0.5 * (err[q] + err[q - 1]) * std::log(l1 / l0);
    fit.meanErrorLinear += 0.5 * (err[q] + err[q - 1]) * (l1 - l0);
  }
  const double span = exact.size() > 1 ? exact.back().lambdaOverA / exact.front().lambdaOverA : 1;
  fit.meanErrorLog /= std::max(std::log(span), 1e-300);
  fit.meanErrorLinear /= std::max(exact.back().lambdaOverA - exact.front().lambdaOverA, 1e-300);
  return fit;
}

namespace {

using Vec = std::array<double, 3>;

ChiParameters fromLog(const Vec& p) {
  return {std::exp(p[0]), std::exp(p[1]), std::exp(p[2])};
}

// Plain Nelder-Mead (reflection, expansion, contraction, shrink) on a 3-vector.
template <typename F>
Vec nelderMead(F f, Vec start, double step, int maxEval, int* evals) {
  std::array<Vec, 4> x;
  std::array<double, 4> fx;
  for (int v = 0; v < 4; ++v) {
    x[v] = start;
    if (v > 0) x[v][v - 1] += step;
    fx[v] = f(x[v]);
  }
  *evals += 4;
  while (*evals < maxEval) {
    std::array<int, 4> o = {0, 1, 2, 3};
    std::sort(o.begin(), o.end(), [&](int a, int b) { return fx[a] < fx[b]; });
    const int best = o[0], worst = o[3], second = o[2];
    if (fx[worst] - fx[best] < 1e-10 * (1.0 + fx[best])) break;
    Vec c{0, 0, 0};
    for (int v : {o[0], o[1], o[2]})
      for (int d = 0; d < 3; ++d) c[d] += x[v][d] / 3.0;
    auto along = [&](double t) {
      Vec p;
      for (int d = 0; d < 3; ++d) p[d] = c[d] + t * (x[worst][d] - c[d]);
      return p;
    };
    const Vec r = along(-1.0);
    const double fr = f(r);
    ++*evals;
    if (fr < fx[best]) {
      const Vec e = along(-2.0);
      const double fe = f(e);
      ++*evals;
      x[worst] = fe < fr ? e : r;
      fx[worst] = std::min(fe, fr);
    } else if (fr < fx[second]) {
      x[worst] = r;
      fx[worst] = fr;
    } else {
      const Vec k = along(fr < fx[worst] ? -0.5 : 0.5);
      const double fk = f(k);
      ++*evals;
      if (fk < std::min(fr, fx[worst])) {
        x[worst] = k;
        fx[worst] = fk;
      } else {
        for (int v : {o[1], o[2], o[3]}) {
          for (int d = 0; d < 3; ++d) x[v][d] = x[best][d] + 0.5 * (x[v][d] - x[best][d]);
          fx[v] = f(x[v]);
        }
        *evals += 3;
      }
    }
  }
  return *std::min_element(x.begin(), x.end(),
                           [&](const Vec& a, const Vec& b) { return f(a) < f(b); });
}

}  // namespace

ChiFit fitChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
              const std::vector<FrequencyPoint>& exact, double maxWeight) {
  auto cost = [&](const Vec& p) {
    const ChiFit e = evaluateChi(kind, a_over_b, nu, nx, ny, fromLog(p), exact);
    return e.meanErrorLog + maxWeight * e.maxError;
  };
  int evals = 0;
  Vec best{};
  double bestCost = 1e300;
  for (const Vec& start : {Vec{std::log(0.3), 0.0, std::log(0.3)}, Vec{std::log(1.0), 0.0, 0.0},
                           Vec{std::log(0.05), std::log(0.8), std::log(0.05)}}) {
    const Vec p = nelderMead(cost, start, 0.7, evals + 1500, &evals);
    const double c = cost(p);
    if (c < bestCost) {
      bestCost = c;
      best = p;
    }
  }
  ChiFit fit = evaluateChi(kind, a_over_b, nu, nx, ny, fromLog(best), exact);
  fit.evaluations = evals;
  return fit;
}

}  // namespace wheel_rail_contact
