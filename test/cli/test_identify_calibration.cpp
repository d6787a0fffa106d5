// identify_calibration's exact cache (doc/data/steady_exact_curves*.csv) is keyed by a/b, ray and e
// alone: a cache solved for another setup must stop the tool, not be read as this setup's curves;
// and its reader (validation/steady_curves.hpp) takes the cache's own columns and nothing else.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/calibration/calibration_table.hpp"
#include "process.hpp"
#include "validation/steady_curves.hpp"

namespace {

const char* const kSetup =
    "# Exact steady creep curves (our half-space solver, 20x20 elements over 1.1a x 1.1b, "
    "Hertz pressure; G 8.2e+10 Pa, nu 0.28, mu 0.3, fz 10000 N, sqrt(ab) 5 mm)\n";
const char* const kHeader = "a_over_b,ray,epsilon,xi,eta,phi,fx,fy,mz\n";
const char* const kPoint = "1,11,0.05,1.8e-05,0,0,-0.050762,0,0\n";

// readSteadyCurves' message for a cache of these lines ("" if it reads them).
std::string readError(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  try {
    wheel_rail_contact::readSteadyCurves(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SteadyCurvesFile, ReadsTheCachesOwnColumns) {
  const std::string path = testing::TempDir() + "steady_curves_ok.csv";
  std::ofstream(path) << kSetup << kHeader << kPoint;
  const auto points = wheel_rail_contact::readSteadyCurves(path);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].ray, "11");
  EXPECT_DOUBLE_EQ(points[0].c.xi, 1.8e-05);
  EXPECT_DOUBLE_EQ(points[0].fx, -0.050762);
  EXPECT_TRUE(wheel_rail_contact::readSteadyCurves(testing::TempDir() + "no_such_cache.csv")
                  .empty());  // a new cache
}

TEST(SteadyCurvesFile, RefusesOtherColumnsExtraFieldsAndBadNumbers) {
  // A curves file (--curves: exact / classic / calibrated columns) is not an exact cache.
  EXPECT_NE(readError("c1.csv", std::string(kSetup) +
                                    "a_over_b,ray,epsilon,xi,eta,phi,fx_exact,fy_exact,mz_exact,"
                                    "fx_classic\n" +
                                    kPoint)
                .find("expected the header"),
            std::string::npos);
  EXPECT_NE(readError("c2.csv", std::string(kSetup) + kPoint).find("expected the header"),
            std::string::npos);  // points without a header
  EXPECT_NE(readError("c3.csv", std::string(kHeader) + "1,11,0.05,1.8e-05,0,0,-0.05,0,0,7\n")
                .find("10 fields"),
            std::string::npos);
  EXPECT_NE(readError("c4.csv", std::string(kHeader) + "1,11,0.05,1.8e-05,0,0,-0.05,0,\n")
                .find("not a finite number"),
            std::string::npos);  // an empty last field
  EXPECT_NE(readError("c5.csv", std::string(kHeader) + "1,11,0.05,1.8e-05x,0,0,-0.05,0,0\n")
                .find(":2: not a finite number: '1.8e-05x'"),
            std::string::npos);  // the line is named
  EXPECT_NE(readError("c6.csv", std::string(kHeader) + "1,11,0.05,1.8e-05,0,0,nan,0,0\n")
                .find("not a finite number"),
            std::string::npos);
  EXPECT_EQ(readError("c7.csv", std::string(kSetup) + kHeader + kPoint), "");
}

TEST(IdentifySteady, StopsWhereTheDefaultCacheIsNotFound) {
  // Run from outside the repository the default (relative) cache is not there: the tool would
  // otherwise start solving every exact point. The timeout turns that into a failure here.
  std::string out;
  const int code = wrc_test::run("cd " + testing::TempDir() + " && timeout 120 " +
                                     std::string(WRC_IDENTIFY_CALIBRATION) + " --nx 20 --ab 1",
                                 &out);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("run from the repository root, or give --exact FILE"), std::string::npos)
      << out;
}

TEST(IdentifySteady, RefusesAnExactCacheSolvedForAnotherSetup) {
  const std::string cache = testing::TempDir() + "identify_calibration_nu028.csv";
  std::ofstream(cache) << kSetup << kHeader << kPoint;
  const std::string before = wrc_test::fileText(cache);
  // Without the check the tool would go on to solve the rays' exact points for minutes: the
  // timeout turns that into a failure here.
  std::string out;
  const int code = wrc_test::run("timeout 120 " + std::string(WRC_IDENTIFY_CALIBRATION) +
                                     " --nu 0.3 --nx 20 --ab 1 --exact " + cache,
                                 &out);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("was solved for another setup"), std::string::npos) << out;
  EXPECT_NE(out.find("nu 0.3,"), std::string::npos) << out;  // the setup asked for
  EXPECT_EQ(wrc_test::fileText(cache), before);              // the cache is left as it was
}

TEST(IdentifyCalibration, DumpsAMeshAsCsvAndConvertsItBackWithoutTheExactCache) {
  // Run outside the repository: neither needs the exact curves.
  const std::string dir = testing::TempDir(), tool = WRC_IDENTIFY_CALIBRATION;
  std::string out;
  ASSERT_EQ(wrc_test::run("cd " + dir + " && " + tool + " --dump 10 --out mesh10.csv", &out), 0)
      << out;
  ASSERT_EQ(
      wrc_test::run("cd " + dir + " && " + tool + " --convert mesh10.csv --out mesh10.bin", &out),
      0)
      << out;
  std::ostringstream shipped;
  wheel_rail_contact::CalibrationTable::shipped().forMesh(10).writeBinary(shipped);
  EXPECT_EQ(wrc_test::fileText(dir + "mesh10.bin"), shipped.str());
  EXPECT_NE(wrc_test::run(tool + " --dump 7", &out), 0);
  EXPECT_NE(out.find("no mesh 7"), std::string::npos) << out;
}
