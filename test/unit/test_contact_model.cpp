// The ContactModel contract every FastSim model keeps: after construction, step() and reset()
// allocate nothing, whatever the input (a simulator's real-time loop calls them). Counted by
// replacing the global operator new in this test binary; only the steps in a counted scope count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"

namespace {
long gAllocations = 0;
bool gCounting = false;
}  // namespace

void* operator new(std::size_t n) {
  if (gCounting) ++gAllocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  return operator new(n);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

using namespace wheel_rail_contact;

namespace {

// Counts the allocations of what runs in its scope.
struct CountAllocations {
  CountAllocations() {
    gAllocations = 0;
    gCounting = true;
  }
  ~CountAllocations() { gCounting = false; }
  long count() const { return gAllocations; }
};

// Every kind of step a run can bring: creepages of each kind with spin coming and going, a
// varying load, the load above fz_max (the fixed mesh grows) and far below it (a coarse
// patch), loss of contact, dt = 0, V = 0, rolling backwards and a reversal, rejected input.
std::vector<StepInput> everyKindOfStep(const ContactParameters& p) {
  std::vector<StepInput> in;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 400; ++k) {
    const double q = 0.05 * k, spin = (k / 40) % 2 ? 2.0 : 0.0;
    StepInput s{1e-4,
                20.0,
                1e-3 * std::sin(q),
                5e-4 * std::cos(0.7 * q),
                spin * std::sin(q),
                p.fz0 * (1.0 + 0.3 * std::sin(0.3 * q))};
    switch (k % 50) {
      case 7:
        s.fz = 3.0 * effectiveFzMax(p);
        break;  // the fixed mesh grows (back to its size at each loss of contact)
      case 8:
        s.fz = 1e-4 * p.fz0;
        break;  // a patch of a node or two on the fixed mesh
      case 9:
        s.fz = 0.0;
        break;  // loss of contact: history cleared
      case 11:
        s.dt = 0.0;
        break;
      case 12:
        s.V = 0.0;
        break;
      case 13:
        s.xi = nan;
        break;  // rejected
      case 14:
        s.dt = -1.0;
        break;
      case 15:
        s.phi = 1e13;
        break;
      default:
        break;
    }
    if (k >= 200 && k < 300) s.V = -s.V;  // backwards, reversing at 200 and 300
    in.push_back(s);
  }
  return in;
}

struct Case {
  const char* model;
  const char* mesh;
};

}  // namespace

TEST(ContactModel, StepAndResetAllocateNothingWhateverTheInput) {
  for (const Case& c : {Case{"steady", "fixed"}, Case{"shen-li", "fixed"}, Case{"nss", "fixed"},
                        Case{"nss", "adaptive"}, Case{"auto", "adaptive"}}) {
    ContactParameters p;
    p.model = c.model;
    p.mesh = c.mesh;
    p.nx = p.ny = 10;
    const auto m = makeContactModel(p);
    const std::vector<StepInput> in = everyKindOfStep(p);
    m->step(in[0]);  // the first step may size what the constructor could not know
    long allocations = 0;
    int notOk = 0;
    {
      const CountAllocations counted;
      for (const StepInput& s : in) notOk += m->step(s).status != StepStatus::kOk;
      m->reset();
      for (const StepInput& s : in) m->step(s);
      allocations = counted.count();
    }
    EXPECT_EQ(allocations, 0) << c.model << " " << c.mesh;
    EXPECT_GE(notOk, 5 * 8) << c.model << " " << c.mesh;  // the odd steps were there
  }
}

TEST(ContactModel, CalibratedStepsWithAChangingAOverBAllocateNothing) {
  // A new a/b re-picks the calibration's ratios: into the storage the model already holds.
  for (const char* model : {"steady", "nss", "auto"}) {
    ContactParameters p;
    p.model = model;
    p.fastsim = FastSimVariant::kCalibrated;
    p.nx = p.ny = 10;
    const auto m = makeContactModel(p);
    std::vector<StepInput> in;
    for (int k = 0; k < 200; ++k) {
      StepInput s{1e-4, 20.0, 2e-3, 5e-4, 1.0, p.fz0};
      const double ab = 1.0 + 0.4 * std::sin(0.1 * k);  // a/b from 0.6 to 1.4 at a constant area
      s.a = p.a0 * std::sqrt(ab * p.b0 / p.a0);
      s.b = s.a / ab;
      in.push_back(s);
    }
    m->step(in[0]);
    long allocations = 0;
    int ok = 0;
    {
      const CountAllocations counted;
      for (const StepInput& s : in) ok += m->step(s).status == StepStatus::kOk;
      allocations = counted.count();
    }
    EXPECT_EQ(allocations, 0) << model;
    EXPECT_EQ(ok, 200) << model;
  }
}

TEST(ContactModel, TheCounterSeesAnAllocation) {
  // The contract above could pass vacuously if the counter missed allocations.
  const CountAllocations counted;
  std::string grown(100, 'x');
  EXPECT_GE(counted.count(), 1) << grown;
}

TEST(ContactModel, TheAdaptiveMeshsOldNameIsRefusedNamingTheNewOne) {
  // mesh "auto" was the adaptive mesh under a name that read like model auto.
  for (const char* model : {"nss", "auto"}) {
    ContactParameters p;
    p.model = model;
    p.mesh = "auto";
    try {
      makeContactModel(p);
      FAIL() << model << ": mesh auto accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "mesh: 'auto' was renamed 'adaptive'");
    }
    p.mesh = "adaptive";
    EXPECT_NO_THROW(makeContactModel(p)) << model;
  }
}
