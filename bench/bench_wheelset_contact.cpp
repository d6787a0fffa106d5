// Cost of WheelsetContact per wheel per step on real profiles (S1002 on UIC60 1:40, the built-in
// ones) at the Manchester benchmark's right-wheel states y = 0.5, 5 and 6.5 mm, the pose
// stepped 0.01 mm per step back and forth over 0.1 mm around the state, as a simulator steps it
// (so each step's load iteration starts warm from the previous one's). The left wheel carries no
// load (its step returns at once), so a step's time is the right wheel's.
//   Geometry: the search at first touch alone, as WheelsetContact does it (direct: one search at
//     z = 0, one more at the closest candidate's touch when that is more than 10 um away; table:
//     one lookup, ContactTable::searchAtTouch).
//   Normal_Table: solveWheelLoad alone on the table's geometry, warm.
//   GeometryNormal: WheelsetContact::step with tangential = false: the search and the normal
//     problem (solveWheelLoad); ..._Cold with warm_start = false.
//   Step: the whole WheelsetContact::step with the model nss (creepages, tangential forces).
//   ModelMade: what a patch's appearance adds to its step: WheelsetContact makes the patch's nss
//     model (makeContactModel at the patch's a, b and fn; here the 0.5 mm state's tread patch).
// Each with the direct search (Search) and with a contact table (Table) covering the states.
// Run:
//   build/devel/lib/wheel_rail_contact/bench_wheelset_contact --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
// (CPU time; the median of the 5 repetitions is the `_median` row).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

using namespace wheel_rail_contact;

namespace {

// A-2.2's right-wheel rows (test/data/profiles/a22_cases.csv) in the benchmark's axes: y mm, yaw
// rad, roll rad, pitch rate rad/s; ours: y and yaw of the other sign, omega = -vpitch.
constexpr double kStates[3][4] = {{0.5, 0.0012, -2.304e-05, -4.34741},
                                  {5.0, 0.012, -0.0003554, -4.33536},
                                  {6.5, 0.0156, -0.004376, -4.27488}};

WheelsetState state(int k, int step) {
  // A triangle wave of 0.01 mm steps over [0, 0.1] mm.
  const int phase = step % 20;
  const double dy_mm = 0.01 * (phase < 10 ? phase : 20 - phase);
  WheelsetState s;
  s.pose.y = -(kStates[k][0] + dy_mm) * 1e-3;
  s.pose.yaw = -kStates[k][1];
  s.pose.roll = kStates[k][2];
  s.motion.V = 2.0;
  s.motion.omega = -kStates[k][3];
  s.fz_left = 0.0;
  s.fz_right = 1e4;
  return s;
}

ContactTableOptions tableOptions() {
  // The default steps, the ranges cut to the states' (the wheel's Y reaches 8.5 mm at 6.5 mm, its
  // roll moving it 2 mm).
  ContactTableOptions o;
  o.max_abs_lateral = 0.012;
  o.max_abs_yaw = 0.02;
  o.max_abs_roll = 0.0075;
  return o;
}

std::shared_ptr<const ContactTable> table() {
  static const auto t =
      std::make_shared<const ContactTable>(ContactSearch{WheelsetTrackData{}}, tableOptions());
  return t;
}

void run(benchmark::State& bs, bool use_table, bool tangential, bool warm) {
  const int k = static_cast<int>(bs.range(0));
  WheelsetContactOptions o;
  if (use_table) o.contact_table = table();
  o.tangential = tangential;
  o.warm_start = warm;
  ContactParameters p;
  p.model = "nss";
  WheelsetContact c(WheelsetTrackData{}, p, o);
  const WheelsetResult first = c.step(state(k, 0), 0.0);
  if (first.right.status != WheelStatus::kOk) bs.SkipWithError(first.right.message.c_str());
  bs.SetLabel(std::to_string(first.right.patches.size()) + " patches");
  const double dt = 1e-5 / 2.0;  // 0.01 mm at V = 2 m/s
  int i = 1;
  for (auto _ : bs) benchmark::DoNotOptimize(c.step(state(k, i++), dt));
}

void GeometryNormal_Search(benchmark::State& s) {
  run(s, false, false, true);
}
void GeometryNormal_Table(benchmark::State& s) {
  run(s, true, false, true);
}
void GeometryNormal_Table_Cold(benchmark::State& s) {
  run(s, true, false, false);
}
void Step_Search(benchmark::State& s) {
  run(s, false, true, true);
}
void Step_Table(benchmark::State& s) {
  run(s, true, true, true);
}

// The direct search at first touch alone, as WheelsetContact::Impl::stepWheel does it.
template <class Searcher>
void geometry(benchmark::State& bs, const Searcher& searcher) {
  const int k = static_cast<int>(bs.range(0));
  int i = 0;
  for (auto _ : bs) {
    WheelsetPose pose = state(k, i++).pose;
    pose.z = 0.0;
    WheelContactGeometry g = searcher.search(WheelSide::kRight, pose);
    if (g.closest >= 0 && std::abs(g.candidates[g.closest].vertical_gap) > 1e-5) {
      pose.z -= g.candidates[g.closest].vertical_gap;
      g = searcher.search(WheelSide::kRight, pose);
    }
    benchmark::DoNotOptimize(g);
  }
}
void Geometry_Search(benchmark::State& s) {
  static const ContactSearch search{WheelsetTrackData{}};
  geometry(s, search);
}
void Geometry_Table(benchmark::State& bs) {
  // The table finds the touching height within one lookup (ContactTable::searchAtTouch).
  const int k = static_cast<int>(bs.range(0));
  int i = 0;
  for (auto _ : bs) {
    WheelsetPose pose = state(k, i++).pose;
    pose.z = 0.0;
    WheelContactGeometry g = table()->searchAtTouch(WheelSide::kRight, &pose, 1e-5);
    benchmark::DoNotOptimize(g);
  }
}

// solveWheelLoad alone on the table's geometries of the 20 poses (computed before the timing, as
// Geometry_Table does), warm from the previous pose's solution as WheelsetContact starts it; the
// label gives the mean number of trials (approaches solved) per step.
void normalTable(benchmark::State& bs, bool continuous_region) {
  const int k = static_cast<int>(bs.range(0));
  std::vector<WheelContactGeometry> g;
  for (int i = 0; i < 20; ++i) {
    WheelsetPose pose = state(k, i).pose;
    pose.z = 0.0;
    g.push_back(table()->searchAtTouch(WheelSide::kRight, &pose, 1e-5));
  }
  NormalOptions cold;
  cold.continuous_region = continuous_region;
  WheelNormal prev = solveWheelLoad(g[0], 1e4, 8.2e10, 0.28, cold);
  long trials = 0, steps = 0;
  int i = 1;
  for (auto _ : bs) {
    NormalOptions o = cold;
    o.start_beyond_touch = prev.vertical_approach - prev.touch_approach;
    o.start_exponent = prev.load_exponent;
    prev = solveWheelLoad(g[i++ % 20], 1e4, 8.2e10, 0.28, o);
    trials += prev.trials;
    ++steps;
  }
  bs.SetLabel(std::to_string(static_cast<double>(trials) / std::max(steps, 1L)) + " trials");
}
void Normal_Table(benchmark::State& bs) {
  normalTable(bs, true);
}
// The same with NormalOptions::continuous_region = false (fn jumps on the 0.5 mm tread's plateau).
void Normal_Table_NoContinuousRegion(benchmark::State& bs) {
  normalTable(bs, false);
}

void ModelMade(benchmark::State& bs) {
  WheelsetContactOptions o;
  o.contact_table = table();
  o.tangential = false;
  WheelsetContact c(WheelsetTrackData{}, ContactParameters{}, o);
  const NormalPatch np = c.step(state(0, 0), 0.0).right.patches.at(0).normal;
  ContactParameters p;  // as WheelsetContact makes a patch's model
  p.model = "nss";
  p.a0 = np.a;
  p.b0 = np.b;
  p.fz0 = np.fn;
  p.fz_max = 0.0;
  makeContactModel(p);  // the shipped tables read once per process, as any first model does
  for (auto _ : bs) benchmark::DoNotOptimize(makeContactModel(p));
}

}  // namespace

// Argument: the state, 0 (y = 0.5 mm), 1 (5 mm), 2 (6.5 mm).
BENCHMARK(Geometry_Search)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(Geometry_Table)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(Normal_Table)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(Normal_Table_NoContinuousRegion)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(GeometryNormal_Search)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(GeometryNormal_Table)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(GeometryNormal_Table_Cold)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(Step_Search)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(Step_Table)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(ModelMade)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
