#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/exact/halfspace_solver.hpp"
#include "csv_rows.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

std::vector<std::vector<std::string>> readCsv(const std::string& path) {
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  return csvRows(in);
}

const std::string kReference = std::string(WRC_SOURCE_DIR) + "/test/data/contact_reference/";

double kalker(CreepageKind k, double ab) {
  const CreepCoefficients c = kalkerCoefficients(ab, 0.28);
  return k == CreepageKind::kXi ? c.c11 : k == CreepageKind::kEta ? c.c22 : c.c23;
}

}  // namespace

TEST(NonSteadyCoefficients, SteadyReproducesKalkersTableAt40x40) {
  // Kalker's table is the continuum; a 40 x 40 grid over 1.1 times the patch sits 0.9-2.3 % above
  // it (how the whole elements cover the ellipse). Required: within 3 %.
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) {
    const CreepCoefficients c = exactSteadyCoefficients(ab, 0.28, 40, 40);
    for (CreepageKind k : kCreepageKinds) {
      const double v = k == CreepageKind::kXi ? c.c11 : k == CreepageKind::kEta ? c.c22 : c.c23;
      EXPECT_NEAR(v, kalker(k, ab), 0.03 * kalker(k, ab)) << "a/b " << ab << " " << toString(k);
    }
  }
}

TEST(NonSteadyCoefficients, ReproducesContactSteadyCoefficientsAt50x50) {
  // CONTACT's own 50 x 50 values (test/data/contact_reference/contact_steady_coefficients.csv):
  // same grid, same discrete normal problem, same scheme (spin slip taken dx/6 downstream, as
  // CONTACT does). 2e-3 relative: we reach 1e-5 except at a/b = 0.2 (up to 9e-4; a boundary element
  // of the normal problem may differ).
  const auto rows = readCsv(kReference + "contact_steady_coefficients.csv");
  ASSERT_EQ(rows.size(), 15u);
  std::map<double, CreepCoefficients> cache;
  for (const auto& r : rows) {
    const double ab = std::stod(r[0]), value = std::stod(r[8]);
    if (!cache.count(ab)) cache[ab] = exactSteadyCoefficients(ab, 0.28, 50, 50);
    const double c = r[7] == "C11" ? cache[ab].c11 : r[7] == "C22" ? cache[ab].c22 : cache[ab].c23;
    EXPECT_NEAR(c, value, 2e-3 * value) << ab << " " << r[7];
  }
}

TEST(NonSteadyCoefficients, ReproducesContactC11Curve) {
  // test/data/contact_reference/contact_c11_ab1.csv (CONTACT, time-domain runs fitted over whole
  // periods). Same scheme in the frequency domain: |C/C_steady| within 2e-4 and phase within
  // 0.02 degrees (we reach 8e-5 and 0.005 degrees, the reference's own fitting precision).
  const auto rows = readCsv(kReference + "contact_c11_ab1.csv");
  ASSERT_EQ(rows.size(), 17u);
  std::map<int, std::unique_ptr<NonSteadyCoefficients>> grids;
  for (const auto& r : rows) {
    const int m = std::stoi(r[3]);
    if (!grids.count(m))
      grids[m] = std::make_unique<NonSteadyCoefficients>(CreepageKind::kXi, 1.0, 0.28, m, m);
    const NonSteadyCoefficients& c = *grids[m];
    const std::complex<double> z = c.at(std::stod(r[2]));
    EXPECT_NEAR(c.steady(), std::stod(r[10]), 1e-5 * c.steady());
    EXPECT_NEAR(std::abs(z) / c.steady(), std::stod(r[11]), 2e-4) << r[2] << " " << m;
    EXPECT_NEAR(std::arg(z) * 180.0 / M_PI, std::stod(r[9]), 0.02) << r[2] << " " << m;
  }
}

TEST(NonSteadyCoefficients, LongWavesTendToSteadyShortWavesLag) {
  for (CreepageKind k : kCreepageKinds) {
    const NonSteadyCoefficients c(k, 0.5, 0.28, 16, 16);
    EXPECT_NEAR(c.at(1e5).real(), c.steady(), 1e-3 * c.steady()) << toString(k);
    EXPECT_LT(std::abs(c.at(2.0)), 0.5 * c.steady()) << toString(k);
    if (k != CreepageKind::kPhi) {
      EXPECT_LT(c.at(5.0).imag(), 0.0) << toString(k);  // a lag
    }
  }
  EXPECT_THROW(NonSteadyCoefficients(CreepageKind::kXi, -1.0, 0.28, 10, 10), std::invalid_argument);
}

TEST(NonSteadyCoefficients, FrequencyDomainEqualsTimeDomainRun) {
  // The transient solver, driven by the step means of cos(2 pi q / lambda) from rest, fitted over
  // whole periods after the start-up has decayed (e^-20), equals the frequency-domain answer to
  // 1e-6 of C_steady. lambda = 30 dx so that periods hold whole steps.
  const int m = 12;
  for (CreepageKind k : kCreepageKinds) {
    const double a = 1.0, b = 1.0 / 1.5, G = 1.0, amp = 1e-6;
    HalfspaceSolver s(HalfspaceGrid::covering(a, b, m, m), G, 0.28);
    s.setHertzPressure(a, b, 1.0);
    const double dx = s.grid().dx, lambda = 30.0 * dx, theta = 2.0 * M_PI * dx / lambda;
    const int skip = 120, fit = 60;
    double A = 0.0, B = 0.0;
    for (int n = 1; n <= skip + fit; ++n) {
      // exact mean of cos(theta q/dx) over the step ending at q_n = n dx
      const double c = (std::sin(theta * n) - std::sin(theta * (n - 1))) / theta * amp;
      const Creepages w{k == CreepageKind::kXi ? c : 0.0, k == CreepageKind::kEta ? c : 0.0,
                        k == CreepageKind::kPhi ? c : 0.0};
      const HalfspaceSolution& r = s.solve(RollingMode::kTransient, w, 1e9);
      if (n <= skip) continue;
      const double f = k == CreepageKind::kXi ? r.fx : r.fy;
      A += 2.0 / fit * f * std::cos(theta * n);
      B += 2.0 / fit * f * std::sin(theta * n);
    }
    const double norm = G * (k == CreepageKind::kPhi ? std::pow(a * b, 1.5) : a * b) * amp;
    const std::complex<double> timeDomain = -std::complex<double>(A, -B) / norm;
    const NonSteadyCoefficients c(k, a / b, 0.28, m, m);
    const std::complex<double> freq = c.at(lambda / a);
    EXPECT_NEAR(std::abs(timeDomain - freq), 0.0, 1e-6 * c.steady()) << toString(k);
  }
}
