// Cost of one step of each FastSim model and mesh (ns per step). Run:
//   build/devel/lib/wheel_rail_contact/bench_fastsim --benchmark_repetitions=9
//     --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true
// (random interleaving spreads the machine's load over every model alike; the `_min` aggregate,
// the least of the repetitions, is the one to compare on a shared machine, whose interruptions only
// ever add time). Each nss row compares
// with steady FastSim on the same mesh: the adaptive mesh with Steady (SteadyModel, mesh fitted to
// the patch), the fixed mesh with SteadyFixedMesh (steady FastSim on nss's fixed mesh). The nss
// rows run a uniform first-order chi; the *Shipped rows the shipped table (second order with spin).
// doc/performance.md's table with ratios, least over whole sweeps: scripts/step_time.sh.
// Instruction counts, which do not depend on the load: scripts/step_cost.sh.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "step_inputs.hpp"

using namespace wheel_rail_contact;

namespace {

void run(benchmark::State& state, const char* model, const char* mesh, bool varyLoad,
         bool shippedChi = false) {
  const auto m = bench::makeModel(model, mesh, static_cast<int>(state.range(0)), shippedChi);
  StepInput in[256];
  for (int k = 0; k < 256; ++k) in[k] = bench::input(k, varyLoad);
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m->step(in[k++ & 255]));
  }
}

void Steady(benchmark::State& s) {
  run(s, "steady", "fitted", true);
}
void SteadyFixedMesh(benchmark::State& s) {
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
// With the shipped chi table (what a user runs): with spin, kind 23's second-order F makes both
// directions' filters second order, and the march carries s2.
void NssFixedShipped(benchmark::State& s) {
  run(s, "nss", "fixed", true, true);
}
void NssAdaptiveShipped(benchmark::State& s) {
  run(s, "nss", "adaptive", true, true);
}
void NssAdaptiveConstantLoadShipped(benchmark::State& s) {
  run(s, "nss", "adaptive", false, true);
}

double least(const std::vector<double>& v) {
  return *std::min_element(v.begin(), v.end());
}

}  // namespace

#define MESHES Arg(10)->Arg(20)->Arg(30)->Arg(40)->ComputeStatistics("min", least)
// The calibrated FastSim (fastsim: calibrated) against the same models classic.
void SteadyCalibrated(benchmark::State& s) {
  run(s, "steady-calibrated", "fitted", true);
}
void SteadyFixedMeshCalibrated(benchmark::State& s) {
  run(s, "steady-calibrated", "fixed", true);
}
void NssFixedCalibrated(benchmark::State& s) {
  run(s, "nss-calibrated", "fixed", true, true);
}
void NssAdaptiveCalibrated(benchmark::State& s) {
  run(s, "nss-calibrated", "adaptive", true, true);
}

BENCHMARK(Steady)->MESHES;
BENCHMARK(SteadyFixedMesh)->MESHES;
BENCHMARK(ShenLi)->MESHES;
BENCHMARK(NssFixed)->MESHES;
BENCHMARK(NssAdaptive)->MESHES;
BENCHMARK(NssAdaptiveConstantLoad)->MESHES;
BENCHMARK(NssFixedShipped)->MESHES;
BENCHMARK(NssAdaptiveShipped)->MESHES;
BENCHMARK(NssAdaptiveConstantLoadShipped)->MESHES;
BENCHMARK(SteadyCalibrated)->MESHES;
BENCHMARK(SteadyFixedMeshCalibrated)->MESHES;
BENCHMARK(NssFixedCalibrated)->MESHES;
BENCHMARK(NssAdaptiveCalibrated)->MESHES;

// The calibrated FastSim's per-step calibration alone (PatchCalibration::step) on the nss
// rows' inputs: the default patch scaled with the load, mu fz, and the eta phi < 0 branch's weight
// following over travel with relaxation length a as NssModel::followBranch does (between the
// branches most of the time: eta changes sign every 25 mm).
void CalibrationStep(benchmark::State& state) {
  const ContactParameters p;
  const PatchCalibration cal =
      CalibrationTable::shipped().forMesh(static_cast<int>(state.range(0))).at(p.a0 / p.b0);
  const CreepCoefficients k = kalkerCoefficients(p.a0 / p.b0, p.nu);
  struct Step {
    double a, b, muFz, opposed;
    Creepages c;
  } steps[256];
  double opposed = -1.0;
  for (int i = 0; i < 256; ++i) {
    const StepInput in = bench::input(i, true);
    const double s = std::cbrt(in.fz / p.fz0), a = p.a0 * s;
    const Creepages c{in.xi, in.eta, in.phi};
    opposed = PatchCalibration::followedBranch(opposed, c, in.V * in.dt, a);
    steps[i] = {a, p.b0 * s, p.mu * in.fz, opposed, c};
  }
  int i = 0;
  for (auto _ : state) {
    const Step& x = steps[i++ & 255];
    benchmark::DoNotOptimize(cal.step(x.a, x.b, p.G, k, x.muFz, x.c, x.opposed));
  }
}
BENCHMARK(CalibrationStep)->Arg(5)->Arg(10)->Arg(20)->ComputeStatistics("min", least);
BENCHMARK_MAIN();
