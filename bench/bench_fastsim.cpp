// Cost of one step of each FastSim model and mesh (ns per step). Run:
//   build/devel/lib/wheel_rail_contact/bench_fastsim --benchmark_repetitions=5 \
//     --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "wheel_rail_contact/nss_model.hpp"
#include "wheel_rail_contact/steady_model.hpp"

using namespace wheel_rail_contact;

namespace {

// Partial slip, combined creepages, and (when varyLoad) a load that changes every step.
StepInput input(int k, bool varyLoad) {
  const double q = 20.0 * 5e-5 * k;
  return {5e-5,
          20.0,
          1.5e-3 * std::cos(2 * M_PI * q / 0.09),
          0.8e-3 * std::sin(2 * M_PI * q / 0.05),
          1.0,
          8e4 * (varyLoad ? 1.0 + 0.25 * std::sin(2 * M_PI * q / 0.12) : 1.0)};
}

void run(benchmark::State& state, const char* model, const char* mesh, bool varyLoad) {
  ContactParameters p;
  p.model = model;
  p.mesh = mesh;
  p.nx = p.ny = static_cast<int>(state.range(0));
  std::unique_ptr<ContactModel> m;
  if (p.model == "steady")
    m = std::make_unique<SteadyModel>(p);
  else
    m = std::make_unique<NssModel>(p, ChiTable::uniform({0.4, 1.1, 0.6}));
  StepInput in[256];
  for (int k = 0; k < 256; ++k) in[k] = input(k, varyLoad);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m->step(in[k++ & 255]));
  }
}

void Steady(benchmark::State& s) {
  run(s, "steady", "fixed", true);
}
void ShenLi(benchmark::State& s) {
  run(s, "shen-li", "fixed", true);
}
void NssFixed(benchmark::State& s) {
  run(s, "nss", "fixed", true);
}
void NssAdaptive(benchmark::State& s) {
  run(s, "nss", "adaptive", true);
}
void NssAdaptiveConstantLoad(benchmark::State& s) {
  run(s, "nss", "adaptive", false);
}

}  // namespace

BENCHMARK(Steady)->Arg(10)->Arg(20)->Arg(30)->Arg(40);
BENCHMARK(ShenLi)->Arg(10)->Arg(20)->Arg(30)->Arg(40);
BENCHMARK(NssFixed)->Arg(10)->Arg(20)->Arg(30)->Arg(40);
BENCHMARK(NssAdaptive)->Arg(10)->Arg(20)->Arg(30)->Arg(40);
BENCHMARK(NssAdaptiveConstantLoad)->Arg(10)->Arg(20)->Arg(30)->Arg(40);
BENCHMARK_MAIN();
