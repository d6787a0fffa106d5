// Cost of the normal problem per patch (solvePatchNormal) and per wheel under a prescribed load
// (solveWheelLoad), on the Manchester benchmark's case, right wheel, 10 kN: the tread at
// 2 mm (Hertz), the tread at 0.5 mm (strips), the gauge corner at 5 mm (two patches, the
// gauge corner timed), the flange at 6.5 mm (strips). Run:
//   build/devel/lib/wheel_rail_contact/bench_patch_normal --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
// Patch/k/1: with NormalOptions::continuous_region = false. WheelLoadWarm: the same with
// NormalOptions::start_beyond_touch from the previous step's solution, its pose 0.01 mm away. The
// contact search is not timed (its geometry is computed once per state).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "wheel_rail_contact/normal/patch_normal.hpp"

using namespace wheel_rail_contact;

namespace {

// A-2.2's right-wheel states (test/data/profiles/a22_cases.csv) in our axes: y and yaw of the
// other sign, roll as given (doc/profiles.md).
struct State {
  double y_mm, yaw, roll;
};
constexpr State kStates[] = {{2.0, 0.0048, -0.0001128},
                             {0.5, 0.0012, -2.304e-05},
                             {5.0, 0.012, -0.0003554},
                             {6.5, 0.0156, -0.004376}};

/// The state's geometry, its y moved by dy_mm, the wheelset lowered to first touch.
WheelContactGeometry geometry(int k, double dy_mm = 0.0) {
  static const ContactSearch search{WheelsetTrackData{}};
  WheelsetPose p;
  p.y = -(kStates[k].y_mm + dy_mm) * 1e-3;
  p.yaw = -kStates[k].yaw;
  p.roll = kStates[k].roll;
  for (int i = 0; i < 3; ++i) {  // down to first touch
    const WheelContactGeometry g = search.search(WheelSide::kRight, p);
    p.z -= g.candidates.at(g.closest).vertical_gap;
  }
  return search.search(WheelSide::kRight, p);
}

/// Patch: one solvePatchNormal at the load's approach; second argument 1:
/// NormalOptions::continuous_region = false (the trial's cost without it, at its own load's
/// approach).
void Patch(benchmark::State& state) {
  const WheelContactGeometry g = geometry(static_cast<int>(state.range(0)));
  NormalOptions o;
  o.continuous_region = state.range(1) == 0;
  const WheelNormal w = solveWheelLoad(g, 1e4, 8.2e10, 0.28, o);
  if (w.status != NormalStatus::kOk) state.SkipWithError(w.message.c_str());
  std::size_t i = static_cast<std::size_t>(g.closest);
  const double ws = w.patches[i].strip_weight;
  state.SetLabel(ws == 0.0   ? std::string("hertz")
                 : ws == 1.0 ? std::string("strips")
                             : "blend, strips' weight " + std::to_string(ws));
  const double approach = w.patches[i].approach;
  for (auto _ : state)
    benchmark::DoNotOptimize(solvePatchNormal(g.candidates[i], approach, 8.2e10, 0.28, o));
}

void WheelLoad(benchmark::State& state) {
  const WheelContactGeometry g = geometry(static_cast<int>(state.range(0)));
  state.SetLabel(std::to_string(g.candidates.size()) + " candidates, " +
                 std::to_string(solveWheelLoad(g, 1e4, 8.2e10, 0.28).trials) + " trials");
  for (auto _ : state) benchmark::DoNotOptimize(solveWheelLoad(g, 1e4, 8.2e10, 0.28));
}

/// Warm start as in a simulator's loop: the previous step's pose 0.01 mm further out, its
/// vertical approach (moved to this step's searched z) the first trial.
void WheelLoadWarm(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const WheelContactGeometry g = geometry(k);
  const WheelContactGeometry prev = geometry(k, 0.01);
  const WheelNormal before = solveWheelLoad(prev, 1e4, 8.2e10, 0.28);
  if (before.status != NormalStatus::kOk) state.SkipWithError(before.message.c_str());
  NormalOptions o;
  o.start_beyond_touch = before.vertical_approach - before.touch_approach;
  o.start_exponent = before.load_exponent;
  state.SetLabel(std::to_string(g.candidates.size()) + " candidates, " +
                 std::to_string(solveWheelLoad(g, 1e4, 8.2e10, 0.28, o).trials) + " trials");
  for (auto _ : state) benchmark::DoNotOptimize(solveWheelLoad(g, 1e4, 8.2e10, 0.28, o));
}

}  // namespace

BENCHMARK(Patch)->ArgsProduct({{0, 1, 2, 3}, {0, 1}});
BENCHMARK(WheelLoad)->DenseRange(0, 3);
BENCHMARK(WheelLoadWarm)->DenseRange(0, 3);
BENCHMARK_MAIN();
