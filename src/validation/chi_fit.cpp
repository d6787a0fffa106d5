#include "validation/chi_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

namespace wheel_rail_contact {

namespace {

// The error measures of one model's ratio curve `ratioAt(lambda/a)` against `exact`.
template <typename RatioAt>
void measure(const RatioAt& ratioAt, const std::vector<FrequencyPoint>& exact, double* meanLog,
             double* meanLinear, double* maxError) {
  std::vector<double> err(exact.size());
  *meanLog = *meanLinear = *maxError = 0.0;
  for (size_t q = 0; q < exact.size(); ++q) {
    err[q] = std::abs(ratioAt(exact[q].lambdaOverA) - exact[q].ratio);
    if (exact[q].lambdaOverA >= 2.0) *maxError = std::max(*maxError, err[q]);
  }
  for (size_t q = 1; q < exact.size(); ++q) {  // trapezoids
    const double l0 = exact[q - 1].lambdaOverA, l1 = exact[q].lambdaOverA;
    *meanLog += 0.5 * (err[q] + err[q - 1]) * std::log(l1 / l0);
    *meanLinear += 0.5 * (err[q] + err[q - 1]) * (l1 - l0);
  }
  const double span = exact.size() > 1 ? exact.back().lambdaOverA / exact.front().lambdaOverA : 1;
  *meanLog /= std::max(std::log(span), 1e-300);
  *meanLinear /= std::max(exact.back().lambdaOverA - exact.front().lambdaOverA, 1e-300);
}

}  // namespace

ChiFit evaluateChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                   const ChiParameters& chi, const std::vector<FrequencyPoint>& exact) {
  ChiFit fit;
  fit.chi = chi;
  const double steady = fastsimSteadyCoefficient(kind, a_over_b, nu, nx, ny);
  measure(
      [&](double l) {
        return fastsimNonSteadyCoefficient(kind, a_over_b, nu, nx, ny, chi, l) / steady;
      },
      exact, &fit.meanErrorLog, &fit.meanErrorLinear, &fit.maxError);
  return fit;
}

SecondOrderFit evaluateSecondOrderChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                                      const SecondOrderChi& chi,
                                      const std::vector<FrequencyPoint>& exact) {
  SecondOrderFit fit;
  fit.chi = chi;
  const double steady = fastsimSteadyCoefficient(kind, a_over_b, nu, nx, ny);
  measure(
      [&](double l) {
        return fastsimSecondOrderCoefficient(kind, a_over_b, nu, nx, ny, chi, l) / steady;
      },
      exact, &fit.meanErrorLog, &fit.meanErrorLinear, &fit.maxError);
  return fit;
}

namespace {

using Vec = std::array<double, 3>;

ChiParameters fromLog(const Vec& p) {
  return {std::exp(p[0]), std::exp(p[1]), std::exp(p[2])};
}

// Plain Nelder-Mead (reflection, expansion, contraction, shrink) on an N-vector.
template <size_t N, typename F>
std::array<double, N> nelderMead(F f, std::array<double, N> start, double step, int maxEval,
                                 int* evals) {
  using P = std::array<double, N>;
  std::array<P, N + 1> x;
  std::array<double, N + 1> fx;
  for (size_t v = 0; v <= N; ++v) {
    x[v] = start;
    if (v > 0) x[v][v - 1] += step;
    fx[v] = f(x[v]);
  }
  *evals += N + 1;
  while (*evals < maxEval) {
    std::array<int, N + 1> o;
    for (size_t v = 0; v <= N; ++v) o[v] = static_cast<int>(v);
    std::sort(o.begin(), o.end(), [&](int a, int b) { return fx[a] < fx[b]; });
    const int best = o[0], worst = o[N], second = o[N - 1];
    if (fx[worst] - fx[best] < 1e-10 * (1.0 + fx[best])) break;
    P c{};
    for (size_t v = 0; v < N; ++v)
      for (size_t d = 0; d < N; ++d) c[d] += x[o[v]][d] / N;
    auto along = [&](double t) {
      P p;
      for (size_t d = 0; d < N; ++d) p[d] = c[d] + t * (x[worst][d] - c[d]);
      return p;
    };
    const P r = along(-1.0);
    const double fr = f(r);
    ++*evals;
    if (fr < fx[best]) {
      const P e = along(-2.0);
      const double fe = f(e);
      ++*evals;
      x[worst] = fe < fr ? e : r;
      fx[worst] = std::min(fe, fr);
    } else if (fr < fx[second]) {
      x[worst] = r;
      fx[worst] = fr;
    } else {
      const P k = along(fr < fx[worst] ? -0.5 : 0.5);
      const double fk = f(k);
      ++*evals;
      if (fk < std::min(fr, fx[worst])) {
        x[worst] = k;
        fx[worst] = fk;
      } else {
        for (size_t rank = 1; rank <= N; ++rank) {
          const int v = o[rank];
          for (size_t d = 0; d < N; ++d) x[v][d] = x[best][d] + 0.5 * (x[v][d] - x[best][d]);
          fx[v] = f(x[v]);
        }
        *evals += N;
      }
    }
  }
  return x[std::min_element(fx.begin(), fx.end()) - fx.begin()];
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

namespace {

// valid() with a margin: where the best F sits on the edge of the Hurwitz region (B < 0, B^2 = 4
// chi1 chi2 chi3 chi5: a node undamped for some step), the table's six decimals could push it
// over (a 5x5 fit did). 10 % clear of the edge in B^2.
bool clearOfTheStabilityEdge(const SecondOrderChi& c) {
  const double B = c.chi1 * c.chi3 + c.chi2 * c.chi5 - c.chi4;
  return B >= 0.0 || B * B < 0.9 * 4.0 * c.chi1 * c.chi2 * c.chi3 * c.chi5;
}

}  // namespace

SecondOrderFit fitSecondOrderChi(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                                 const std::vector<FrequencyPoint>& exact, double maxWeight,
                                 double maxHighFrequencyGain) {
  // All five chi are >= 0 in a stable F (SecondOrderChi::valid), so fit their logarithms; an
  // unstable F is refused, a high-frequency gain above the bound pays for its excess.
  using P = std::array<double, 5>;
  auto fromLog5 = [](const P& p) {
    return SecondOrderChi{std::exp(p[0]), std::exp(p[1]), std::exp(p[2]), std::exp(p[3]),
                          std::exp(p[4])};
  };
  auto cost = [&](const P& p) {
    const SecondOrderChi chi = fromLog5(p);
    if (!chi.valid() || !clearOfTheStabilityEdge(chi)) return 1e9;
    const SecondOrderFit e = evaluateSecondOrderChi(kind, a_over_b, nu, nx, ny, chi, exact);
    const double excess = std::max(0.0, chi.highFrequencyGain() - maxHighFrequencyGain);
    const double c = e.meanErrorLog + maxWeight * e.maxError + excess;
    return std::isfinite(c) ? c : 1e9;
  };
  // Two starts: the best first-order F with a weak second-order pair (a near-cancelling zero and
  // pole), and a typical spin F (a/b = 0.5..2 land near chi1 0.4 chi2, chi3 0.3, chi4 0.06 chi2,
  // chi5 0.02), whose basin the first start can miss. From each, restart the simplex from its
  // best point with shrinking steps: the max term makes the cost non-smooth, where one
  // Nelder-Mead run stalls early.
  const ChiFit first = fitChi(kind, a_over_b, nu, nx, ny, exact, maxWeight);
  int evals = first.evaluations;
  const double c2 = first.chi.chi2;
  P best{};
  double bestCost = 1e300;
  for (const P& start :
       {P{std::log(std::max(first.chi.chi1, 1e-3)), std::log(c2), std::log(first.chi.chi3),
          std::log(0.02 * first.chi.chi1), std::log(0.02)},
        P{std::log(0.4 * c2), std::log(c2), std::log(0.3), std::log(0.06 * c2), std::log(0.02)}}) {
    P p = start;
    for (int round = 0; round < 8; ++round)
      p = nelderMead(cost, p, 0.5 / (1.0 + 0.5 * round), evals + 1500, &evals);
    const double c = cost(p);
    if (c < bestCost) {
      bestCost = c;
      best = p;
    }
  }
  SecondOrderFit fit = evaluateSecondOrderChi(kind, a_over_b, nu, nx, ny, fromLog5(best), exact);
  fit.evaluations = evals;
  return fit;
}

}  // namespace wheel_rail_contact
