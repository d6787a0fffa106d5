// step_cost: runs steps of one model so that callgrind can count the instructions of exactly those
// steps (load-independent, unlike wall clock). scripts/step_cost.sh runs every model and mesh:
//   valgrind --tool=callgrind --toggle-collect='*runSteps*'
//     build/devel/lib/wheel_rail_contact/step_cost MODEL MESH N LOAD STEPS
// MODEL steady|shen-li|nss, MESH fixed|adaptive (steady: fitted, SteadyModel, or fixed, on the
// mesh nss fixed uses), N nodes per strip and strips, LOAD vary|constant; an optional last
// argument "shipped" gives nss the shipped chi table (bench::makeModel).
// The first 256 steps (a warm-up that fills the history) are not counted.
#include <cstdio>
#include <string>

#include "step_inputs.hpp"

using namespace wheel_rail_contact;

namespace {

__attribute__((noinline)) double runSteps(ContactModel& m, const StepInput* in, int steps) {
  double sum = 0.0;
  for (int k = 0; k < steps; ++k) sum += m.step(in[k & 255]).fx;
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6 && !(argc == 7 && std::string(argv[6]) == "shipped")) {
    std::fprintf(stderr, "usage: step_cost MODEL MESH N vary|constant STEPS [shipped]\n");
    return 2;
  }
  const auto m = bench::makeModel(argv[1], argv[2], std::stoi(argv[3]), argc == 7);
  StepInput in[256];
  for (int k = 0; k < 256; ++k) in[k] = bench::input(k, std::string(argv[4]) == "vary");
  for (int k = 0; k < 256; ++k) m->step(in[k]);
  std::printf("%.17g\n", runSteps(*m, in, std::stoi(argv[5])));
  return 0;
}
