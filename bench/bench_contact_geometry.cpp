// Cost of a wheel's contact geometry: the direct contact search against a lookup in the contact
// table (per wheel), at the Manchester benchmark's states (both wheels, each lowered until
// its closest candidate overlaps by 50 micrometres, a loaded wheel), and the table's build.
// Run:
//   build/devel/lib/wheel_rail_contact/bench_contact_geometry --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
// (the `_min` aggregate is the one to compare on a shared machine).
#include <benchmark/benchmark.h>

#include <vector>

#include "wheel_rail_contact/profiles/contact_table.hpp"

using namespace wheel_rail_contact;

namespace {

// Case A-2.2's right-wheel states (test/data/profiles/a22_cases.csv: y mm, yaw rad, roll rad, in
// the benchmark's axes; ours: y and yaw of the other sign, doc/profiles.md).
const double kA22[21][3] = {
    {0, 0, 0},
    {0.5, 0.0012, -2.304e-05},
    {1, 0.0024, -5.049e-05},
    {1.5, 0.0036, -8.103e-05},
    {2, 0.0048, -0.0001128},
    {2.5, 0.006, -0.0001457},
    {3, 0.0072, -0.0001803},
    {3.5, 0.0084, -0.0002168},
    {4, 0.0096, -0.0002557},
    {4.5, 0.0108, -0.0002977},
    {5, 0.012, -0.0003554},
    {5.5, 0.0132, -0.0004777},
    {6, 0.0144, -0.0006272},
    {6.5, 0.0156, -0.004376},
    {7, 0.0168, -0.006393},
    {7.5, 0.018, -0.007642},
    {8, 0.0192, -0.008606},
    {8.5, 0.0204, -0.009408},
    {9, 0.0216, -0.0101011},
    {9.5, 0.0228, -0.0107139},
    {10, 0.0240, -0.0112643},
};

struct Query {
  WheelSide side;
  WheelsetPose pose;
};

const ContactSearch& search() {
  static const ContactSearch s{WheelsetTrackData()};
  return s;
}

const ContactTable& table() {
  static const ContactTable t{search()};
  return t;
}

std::vector<Query> queries() {
  std::vector<Query> q;
  for (const auto& c : kA22)
    for (WheelSide side : {WheelSide::kRight, WheelSide::kLeft}) {
      WheelsetPose p;
      p.y = -c[0] * 1e-3;
      p.yaw = -c[1];
      p.roll = c[2];
      const WheelContactGeometry g = search().search(side, p);
      p.z -= g.candidates[g.closest].vertical_gap + 50e-6;
      q.push_back({side, p});
    }
  return q;
}

void DirectSearch(benchmark::State& state) {
  const std::vector<Query> q = queries();
  std::size_t k = 0;
  for (auto _ : state) {
    const Query& x = q[k++ % q.size()];
    benchmark::DoNotOptimize(search().search(x.side, x.pose));
  }
}

void TableLookup(benchmark::State& state) {
  const std::vector<Query> q = queries();
  table();  // built before the timing
  std::size_t k = 0;
  for (auto _ : state) {
    const Query& x = q[k++ % q.size()];
    benchmark::DoNotOptimize(table().search(x.side, x.pose));
  }
}

void TableBuild(benchmark::State& state) {
  std::size_t bytes = 0, nodes = 0;
  for (auto _ : state) {
    const ContactTable t{search()};
    bytes = t.bytes();
    nodes = t.nodes() * t.tables();
  }
  state.counters["MB"] = bytes * 1e-6;
  state.counters["nodes"] = static_cast<double>(nodes);
}

}  // namespace

BENCHMARK(DirectSearch)->Unit(benchmark::kMicrosecond);
BENCHMARK(TableLookup)->Unit(benchmark::kMicrosecond);
BENCHMARK(TableBuild)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(1);

BENCHMARK_MAIN();
