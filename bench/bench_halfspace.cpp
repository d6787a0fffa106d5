// Cost of the exact half-space reference: one transient rolling step (dq = dx) at 20x20, 30x30 and
// 40x40 elements, in full adhesion and in partial slip, and one whole non-steady coefficient curve.
// Run: build/devel/lib/wheel_rail_contact/bench_halfspace (or build/bench_halfspace).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/exact/halfspace_solver.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

// a = 6 mm, b = 4 mm, fz = 80 kN; full adhesion: mu = 1000 (as CONTACT's reference runs; with mu =
// 0.3 the lightest edge elements slip at any creepage), partial slip: mu = 0.3. The creepage
// oscillates with wavelength 10a around xi0, so every step changes the traction (a steady state
// would converge in one sweep).
void transientStep(benchmark::State& state, double xi0, double mu) {
  const int m = static_cast<int>(state.range(0));
  const double a = 6e-3, b = 4e-3, fz = 8e4;
  HalfspaceSolver s(HalfspaceGrid::covering(a, b, m, m), 8.2e10, 0.28);
  s.setHertzPressure(a, b, fz);
  const double dx = s.grid().dx;
  long n = 0;
  auto creep = [&](long k) {
    const double xi = xi0 * (1.0 + 0.5 * std::sin(2.0 * M_PI * k * dx / (10.0 * a)));
    return Creepages{xi, 0.3 * xi, 0.0};
  };
  for (; n < 3 * m; ++n) s.solve(RollingMode::kTransient, creep(n), mu);  // past the start-up
  long sweeps = 0, steps = 0;
  double adhesion = 0.0;
  for (auto _ : state) {
    const HalfspaceSolution& r = s.solve(RollingMode::kTransient, creep(n++), mu);
    sweeps += r.iterations;
    adhesion += r.adhesionFraction;
    ++steps;
    benchmark::DoNotOptimize(r.fx);
  }
  state.counters["sweeps_per_step"] = static_cast<double>(sweeps) / steps;
  state.counters["adhesion_fraction"] = adhesion / steps;
}

void BM_TransientStepFullAdhesion(benchmark::State& state) {
  transientStep(state, 1e-4, 1000.0);
}
void BM_TransientStepPartialSlip(benchmark::State& state) {
  transientStep(state, 6e-4, 0.3);
}

// One C11 curve: build (normal problem, folded matrices, Hessenberg reduction) plus 20 values of
// lambda/a from 1 to 100 and the steady coefficient.
void BM_NonSteadyCurve(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  std::vector<double> lambdas;
  for (int k = 0; k < 20; ++k) lambdas.push_back(std::pow(10.0, 2.0 * k / 19.0));
  for (auto _ : state) {
    const NonSteadyCoefficients c(CreepageKind::kXi, 1.0, 0.28, m, m);
    double sum = c.steady();
    for (double l : lambdas) sum += c.at(l).real();
    benchmark::DoNotOptimize(sum);
  }
}

}  // namespace

BENCHMARK(BM_TransientStepFullAdhesion)->Arg(20)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TransientStepPartialSlip)->Arg(20)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NonSteadyCurve)->Arg(20)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
