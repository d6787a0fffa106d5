#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../../src/cli/cli.hpp"
#include "core/models/exact_model.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {

ContactParameters coarse() {
  ContactParameters p;
  p.model = "exact";
  p.nx = 16;
  p.ny = 16;
  p.fz_max = p.fz0;  // grid exactly over the reference patch
  return p;
}

}  // namespace

TEST(ExactModel, StatusRules) {
  ExactModel m(coarse());
  EXPECT_EQ(m.name(), "exact");
  StepOutput o = m.step({0.0, 20.0, 1e-3, 0, 0, 8e4});
  EXPECT_EQ(o.status, StepStatus::kOk);
  EXPECT_EQ(o.fx, 0.0);  // from rest, nothing rolled yet
  o = m.step({1e-3, 20.0, 1e-3, 0, 0, 8e4});
  EXPECT_LT(o.fx, 0.0);
  const double held = o.fx;
  o = m.step({1e-3, 0.0, 1e-3, 0, 0, 8e4});
  EXPECT_EQ(o.status, StepStatus::kStandstill);
  EXPECT_EQ(o.fx, held);
  m.reset();
  o = m.step({0.0, 0.0, 1e-3, 0, 0, 8e4});  // starting at rest
  EXPECT_EQ(o.status, StepStatus::kStandstill);
  EXPECT_EQ(o.fx, 0.0);
  o = m.step({1e-3, 0.0, 1e-3, 0, 0, 8e4});
  EXPECT_EQ(m.subSteps(), 0);
  o = m.step({1e-3, 20.0, 1e-3, 0, 0, 8e4});  // 10 mm rolled (trapezoid from rest)
  EXPECT_EQ(m.subSteps(), static_cast<int>(std::floor(0.01 / (2.2 * 6e-3 / 16))));
  EXPECT_EQ(m.step({1e-3, -1.0, 0, 0, 0, 8e4}).status, StepStatus::kOk);  // backwards: mirrored
  EXPECT_EQ(m.step({1e-3, NAN, 0, 0, 0, 8e4}).status, StepStatus::kRejected);
  EXPECT_EQ(m.step({1e-3, 20.0, 0, 0, 0, 2e5}).status, StepStatus::kRejected);  // above fz_max
  o = m.step({1e-3, 20.0, 1e-3, 0, 0, 0.0});
  EXPECT_EQ(o.status, StepStatus::kNoLoad);
  EXPECT_EQ(o.fx, 0.0);
  EXPECT_THROW(
      [] {
        ContactParameters p = coarse();
        p.nx = p.ny = 100;
        ExactModel big(p);
      }(),
      std::invalid_argument);
  ContactParameters adaptive = coarse();
  adaptive.mesh = "adaptive";
  EXPECT_THROW(ExactModel{adaptive}, std::invalid_argument);
}

TEST(ExactModel, SubStepsOfOneElementAndSteadyLimit) {
  // Rows 1 ms apart at 20 m/s roll 20 mm = 20 mm / dx sub-steps (dx = 2.2 a0 / 16); constant
  // small creepage: after 120 mm (18 e-foldings of the start-up) the force is the steady linear
  // one of the same grid (1e-6).
  const ContactParameters p = coarse();
  ExactModel m(p);
  const double dx = 2.2 * p.a0 / p.nx, xi = 1e-6;
  m.step({0.0, 20.0, xi, 0, 0, p.fz0});
  double carried = 0.0;
  StepOutput o;
  for (int k = 0; k < 6; ++k) {
    o = m.step({1e-3, 20.0, xi, 0, 0, p.fz0});
    const double total = carried + 0.02;
    EXPECT_EQ(m.subSteps(), static_cast<int>(std::floor(total / dx)));
    carried = total - m.subSteps() * dx;
  }
  const double c11 = exactSteadyCoefficient(CreepageKind::kXi, p.a0 / p.b0, p.nu, p.nx, p.ny);
  EXPECT_NEAR(o.fx, -p.G * p.a0 * p.b0 * c11 * xi, 1e-6 * p.G * p.a0 * p.b0 * c11 * xi);
  EXPECT_DOUBLE_EQ(o.adhesionFraction, 1.0);
}

TEST(ExactModel, ResetReproducesAFreshModelAndSaturates) {
  const ContactParameters p = coarse();
  ExactModel m(p), fresh(p);
  const StepInput rows[] = {
      {0.0, 10.0, 2e-3, 0, 0, 6e4}, {5e-4, 10.0, 5e-3, 1e-3, 0, 7e4}, {5e-4, 12.0, 0.1, 0, 0, 8e4}};
  for (const auto& r : rows) m.step(r);
  m.reset();
  StepOutput a, b;
  for (const auto& r : rows) {
    a = m.step(r);
    b = fresh.step(r);
    EXPECT_EQ(a.fx, b.fx);
    EXPECT_EQ(a.fy, b.fy);
  }
  EXPECT_NEAR(a.fx, -p.mu * 8e4, 1e-5 * p.mu * 8e4);  // full sliding: mu fz
}

TEST(ExactModel, CliFreqPrintsTheContract) {
  std::ostringstream out, err;
  ASSERT_EQ(runCli({"freq", "--model", "exact", "--kind", "eta", "--ab", "0.5", "--lambda-over-a",
                    "2,20", "--nx", "14", "--ny", "14"},
                   out, err),
            0)
      << err.str();
  std::istringstream in(out.str());
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("lambda_over_a,c_real,c_imag,magnitude,phase_deg,c_steady", 0), 0u);
  int rows = 0;
  while (std::getline(in, row)) ++rows;
  EXPECT_EQ(rows, 2);
  std::ostringstream out3, err3;
  EXPECT_NE(
      runCli({"freq", "--model", "exact", "--kind", "zeta", "--ab", "1", "--lambda-over-a", "2"},
             out3, err3),
      0);
}

TEST(ExactModel, CliRunWritesOneRowPerScenarioRow) {
  // Rows spaced 0, 0.1 mm, 5 mm and 60 mm of rolling apart (dx = 0.825 mm at 16 x 16): the model
  // sub-steps internally and still writes exactly one row per input row, at its t.
  const std::string path = ::testing::TempDir() + "exact_rows.csv";
  std::ofstream(path) << "t,V,xi,eta,phi,fz\n0,10,1e-3,0,0,8e4\n0.00001,10,1e-3,0,0,8e4\n"
                         "0.00051,10,1e-3,0,0,8e4\n0.00651,10,-1e-3,0,0,7e4\n";
  std::ostringstream out, err;
  ASSERT_EQ(runCli({"run", "--scenario", path, "--model", "exact", "--nx", "16", "--ny", "16",
                    "--fz_max", "8e4"},
                   out, err),
            0)
      << err.str();
  std::istringstream in(out.str());
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[4].rfind("0.0065", 0), 0u);
  EXPECT_NE(lines[4].find(",ok"), std::string::npos);
  EXPECT_GT(std::stod(lines[4].substr(lines[4].find(',') + 1)), 0.0);  // xi < 0: Fx > 0
}
