// contact_cli wheelset: its --config (the wheelset and track keys beside the model's parameters)
// and the command itself on the Manchester benchmark's case.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../src/cli/cli.hpp"
#include "../../src/cli/config_yaml.hpp"
#include "cli_test_helpers.hpp"
#include "csv_rows.hpp"
#include "wheel_rail_contact/profiles/profile.hpp"
#include "wheel_rail_contact/wheelset/wheelset_scenario.hpp"

using namespace wheel_rail_contact;

namespace {

std::string configErrorOf(const std::string& yaml) {
  ContactParameters p;
  WheelsetConfig w;
  try {
    loadWheelsetConfigYaml(writeTemp("wbad.yaml", yaml), &p, &w);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string kWheel = std::string(WRC_SOURCE_DIR) + "/config/profiles/MBench_S1002_v3.prw";
const std::string kRail = std::string(WRC_SOURCE_DIR) + "/config/profiles/MBench_UIC60_v3.prr";
const char* const kHeader =
    "t,wheel,patch,y_rail,z_rail,y_wheel,contact_angle,rolling_radius,xi,eta,phi,fn,fx,fs,mz,a,b,"
    "pmax,status";

/// The benchmark's right-wheel states as a wheelset scenario, one per second, made from
/// test/data/profiles/a22_cases.csv with doc/profiles.md's mapping to our REP 103 axes:
/// y = -y_bench, yaw = -yaw_bench, roll = roll_bench, omega = -vpitch. Returns the file's path.
/// Which: all 21 states, the centred one (y = 0) alone, or the 20 others.
enum class A22 { kAll, kCentred, kShifted };
std::string a22Scenario(std::vector<double>* y_mm, A22 which = A22::kAll) {
  std::ifstream in(std::string(WRC_SOURCE_DIR) + "/test/data/profiles/a22_cases.csv");
  std::ostringstream s;
  s << "t,y,yaw,roll,V,omega,fz\n";
  std::string line;
  int t = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("right,", 0) != 0) continue;
    std::vector<std::string> f;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    // wheel,case,y_mm,yaw_rad,roll_rad,fz_N,vs_mm_s,vpitch_rad_s
    const bool centred = std::stod(f[2]) == 0.0;
    if ((which == A22::kCentred && !centred) || (which == A22::kShifted && centred)) continue;
    y_mm->push_back(std::stod(f[2]));
    s.precision(17);
    s << t++ << "," << -std::stod(f[2]) * 1e-3 << "," << -std::stod(f[3]) << "," << std::stod(f[4])
      << "," << std::stod(f[6]) * 1e-3 << "," << -std::stod(f[7]) << "," << std::stod(f[5]) << "\n";
  }
  EXPECT_EQ(y_mm->size(), which == A22::kAll ? 21u : which == A22::kCentred ? 1u : 20u);
  return writeTemp("a22_wheelset.csv", s.str());
}

}  // namespace

TEST(WheelsetConfig, KeysGoToTheTrackTheProfileReaderAndTheParameters) {
  const std::string f = writeTemp("w.yaml",
                                  "nominal_radius: 0.45\nflange_back_distance: 1.36\n"
                                  "flange_back_position: -0.07\ngauge: 1.432\ngauge_depth: 0.015\n"
                                  "rail_inclination: 0.025\ncant: 0.01\n"
                                  "profile_length_unit: mm\nprofile_lateral_axis: toward_gauge\n"
                                  "profile_vertical_axis: up\nprofile_smoothing_length: 5e-4\n"
                                  "mu: 0.25\nmodel: steady\nframe_id: left\n");
  ContactParameters p;
  WheelsetConfig w;
  loadWheelsetConfigYaml(f, &p, &w);
  EXPECT_EQ(w.track.nominal_radius, 0.45);
  EXPECT_EQ(w.track.flange_back_distance, 1.36);
  EXPECT_EQ(w.track.flange_back_position, -0.07);
  EXPECT_EQ(w.track.gauge, 1.432);
  EXPECT_EQ(w.track.gauge_depth, 0.015);
  EXPECT_EQ(w.track.rail_inclination, 0.025);
  EXPECT_EQ(w.cant, 0.01);  // the scenario's default cant
  EXPECT_EQ(w.profile_read.length_unit, 1e-3);
  EXPECT_EQ(w.profile_read.lateral, LateralAxis::kTowardGauge);
  EXPECT_EQ(w.profile_read.vertical, VerticalAxis::kUp);
  EXPECT_EQ(w.profile_read.smoothing_length, 5e-4);
  EXPECT_EQ(p.mu, 0.25);
  EXPECT_EQ(p.model, "steady");
}

TEST(WheelsetConfig, DefaultsAreTheBenchmarksAndDocumented) {
  const WheelsetConfig w;
  const WheelsetTrackData d;
  EXPECT_EQ(w.track.gauge, d.gauge);
  EXPECT_EQ(w.profile_read.length_unit, 0.0);  // the file says
  for (const ParameterDoc& doc : wheelsetParameterDocs()) {
    WheelsetConfig set;
    if (doc.default_value == "file") continue;
    EXPECT_TRUE(setWheelsetParameter(&set, doc.name, doc.default_value)) << doc.name;
  }
  WheelsetConfig set;
  EXPECT_FALSE(setWheelsetParameter(&set, "mu", "0.3"));
}

TEST(WheelsetConfig, ErrorsNameTheKeyAndTheFile) {
  EXPECT_EQ(configErrorOf("gauge: wide\n").rfind("gauge: expected a finite number, got 'wide'", 0),
            0u);
  EXPECT_EQ(configErrorOf("cant: .nan\n").rfind("cant: expected a finite number", 0), 0u);
  EXPECT_EQ(configErrorOf("cant: 0.3\n").rfind("cant: must be within +-0.2 rad, got '0.3'", 0), 0u);
  EXPECT_EQ(configErrorOf("profile_length_unit: -1\n").rfind("profile_length_unit: must be > 0", 0),
            0u);
  EXPECT_EQ(configErrorOf("profile_lateral_axis: left\n").rfind("profile_lateral_axis:", 0), 0u);
  EXPECT_EQ(configErrorOf("profile_vertical_axis: z\n").rfind("profile_vertical_axis:", 0), 0u);
  EXPECT_EQ(configErrorOf("guage: 1.435\n").rfind("guage: unknown parameter", 0), 0u);
  EXPECT_NE(configErrorOf("gauge: wide\n").find("(in '"), std::string::npos);
  EXPECT_EQ(configErrorOf(""), "(no error)");
}

/// Runs the command (--model steady) on the benchmark's states `which` and checks what holds for
/// every row: the header, no NaN, a patch on each wheel in every case, the status, pmax > 0. Fills
/// per wheel and case the vertical load the patches carry, and the right wheel's most loaded
/// patch: its rail point, contact angle and slot.
struct A22Run {
  std::vector<double> y_mm;
  std::map<std::string, std::vector<double>> load;
  std::vector<double> railY, angle;
  std::vector<std::string> zone;
};
A22Run runA22(A22 which) {
  A22Run a;
  const std::string scenario = a22Scenario(&a.y_mm, which);
  const size_t n = a.y_mm.size();
  const CliResult r = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail,
                           "--scenario", scenario, "--model", "steady"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  std::istringstream in(r.out);
  const auto rows = csvRows(in);
  EXPECT_GE(rows.size(), 2 * n + 1);
  if (rows.empty()) return a;
  std::string header;
  for (const std::string& c : rows[0]) header += (header.empty() ? "" : ",") + c;
  EXPECT_EQ(header, kHeader);
  a.load["left"].assign(n, 0.0);
  a.load["right"].assign(n, 0.0);
  a.railY.assign(n, 0.0);
  a.angle.assign(n, 0.0);
  a.zone.assign(n, "");
  std::vector<double> fnMax(n, 0.0);
  for (size_t k = 1; k < rows.size(); ++k) {
    const auto& row = rows[k];
    if (row.size() != 19u) {
      ADD_FAILURE() << "row " << k << ": " << row.size() << " fields";
      continue;
    }
    if (row[2] == "none") {  // every case of the benchmark has contact on both wheels
      ADD_FAILURE() << "t = " << row[0] << ", " << row[1] << " wheel: " << row[18];
      continue;
    }
    // ok on every patch: the conformal flange patch's too (long and narrow, a/b beyond Kalker's
    // table [0.1, 10]), whose strips the model marches, with tangential forces.
    EXPECT_EQ(row[18], "ok") << k;
    EXPECT_GT(std::hypot(std::stod(row[12]), std::stod(row[13])), 0.0) << k;
    const size_t c = static_cast<size_t>(std::lround(std::stod(row[0])));
    if (c >= n) {
      ADD_FAILURE() << "row " << k << ": t = " << row[0];
      continue;
    }
    const double fn = std::stod(row[11]), delta = std::stod(row[6]);
    a.load[row[1]][c] += fn * std::cos(delta);
    EXPECT_GT(std::stod(row[17]), 0.0);  // pmax
    if (row[1] == "right" && fn > fnMax[c]) {
      fnMax[c] = fn;
      a.railY[c] = std::stod(row[3]);
      a.angle[c] = delta;
      a.zone[c] = row[2];
    }
  }
  // Each wheel's patches carry its 10 kN: the normal forces' vertical components add up to it.
  for (const auto& w : a.load)
    for (size_t c = 0; c < n; ++c)
      EXPECT_NEAR(w.second[c], 1e4, 10.0) << w.first << " wheel at y = " << a.y_mm[c] << " mm";
  return a;
}

TEST(ContactCliWheelset, ManchesterA22ThroughTheCommand) {
  const A22Run a = runA22(A22::kShifted);
  ASSERT_EQ(a.zone.size(), 20u);
  // The contact point on the rail jumps to the flange between 6 and 7 mm: before it the gauge
  // corner, after it the flange, and the jump is more than twice any step on the tread (0.5 to
  // 4.5 mm; at 5 mm the contact jumps to the gauge corner).
  int at6 = -1, at7 = -1;
  for (int c = 0; c < 20; ++c) {
    if (a.y_mm[c] == 6.0) at6 = c;
    if (a.y_mm[c] == 7.0) at7 = c;
  }
  ASSERT_EQ(at7, at6 + 2);
  EXPECT_NE(a.zone[at6].rfind("flange", 0), 0u) << a.zone[at6];
  EXPECT_EQ(a.zone[at7].rfind("flange", 0), 0u) << a.zone[at7];
  EXPECT_GT(a.angle[at7], 0.6);
  EXPECT_LT(a.angle[at6], 0.6);
  double tread = 0.0;
  for (int c = 1; c < 20 && a.y_mm[c] <= 4.5; ++c) {
    EXPECT_EQ(a.zone[c].rfind("tread", 0), 0u) << a.zone[c];
    tread = std::max(tread, std::abs(a.railY[c] - a.railY[c - 1]));
  }
  EXPECT_GT(std::abs(a.railY[at7] - a.railY[at6]), 2.0 * tread);
}

TEST(ContactCliWheelset, ManchesterA22CentredWheelsetCarriesItsLoad) {
  // y = 0: each wheel touches its rail at two tread points behind a ridge lower than the 10 kN
  // approach (doc/profiles.md). The load must be carried all the same (runA22's checks).
  runA22(A22::kCentred);
}

TEST(ContactCliWheelset, AWheelWithoutContactGetsOneRowWithItsStatus) {
  const std::string f = writeTemp("w_noload.csv",
                                  "t,y,yaw,roll,V,omega,fz_left,fz_right\n"
                                  "0,-0.0005,-0.0012,-2.304e-05,2,4.34741,0,1e4\n");
  const CliResult r = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail,
                           "--scenario", f, "--model", "steady"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(r.out);
  const auto rows = csvRows(in);
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(rows[1][1], "left");
  EXPECT_EQ(rows[1][2], "none");
  EXPECT_EQ(rows[1][18], "no_load");
  for (int col : {11, 12, 13, 14}) EXPECT_EQ(rows[1][col], "0") << col;  // fn, fx, fs, mz
  EXPECT_EQ(rows[2][1], "right");
  EXPECT_EQ(rows[2][18], "ok");
}

TEST(ContactCliWheelset, BadFilesAndOptionsAreRefusedNamingThem) {
  const std::string good = writeTemp("w_good.csv", "t,y,yaw,roll,V,omega,fz\n0,0,0,0,2,4.3,1e4\n");
  const std::string bad =
      writeTemp("w_bad.csv", "t,y,yaw,roll,V,omega,fz\n0,0,0,0,2,4.3,1e4\n1,0,0,zz,2,4.3,1e4\n");
  CliResult r =
      cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail, "--scenario", bad});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("w_bad.csv:3: field 'roll': not a number ('zz')"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.out, "");  // nothing half-written

  const std::string profile = writeTemp("w_rail.csv", "# unit: mm\n0,0\n1,x\n");
  r = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", profile, "--scenario", good});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("w_rail.csv:3:"), std::string::npos) << r.err;

  // A rail file read as a wheel: the profile's kind is refused.
  r = cli({"wheelset", "--wheel-profile", kRail, "--rail-profile", kRail, "--scenario", good});
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(r.err.empty());

  r = cli({"wheelset", "--rail-profile", kRail, "--scenario", good});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("wheelset: --wheel-profile FILE is required"), std::string::npos) << r.err;

  const std::string config = writeTemp("w_c.yaml", "gauge: 3\n");
  r = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail, "--scenario", good,
           "--config", config});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("gauge"), std::string::npos) << r.err;

  r = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail, "--scenario", good,
           "--mu", "-1"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("mu"), std::string::npos) << r.err;
}

TEST(ContactCliWheelset, EachRowTakesItsCantColumnOrElseTheConfigsCant) {
  // A wheelset on its gauge corner in a 200 m left curve: the rows' cant column, and without it
  // --config's cant (0 without either), give the same rows for the same cant (steady: no
  // history; the same previous row, so the same warm start), and another cant another spin.
  const std::string state = "-0.0055,-0.0132,-0.0004777,2,4.33189,1e4,0.005";
  const std::string column =
      writeTemp("w_cant.csv", "t,y,yaw,roll,V,omega,fz,curvature,cant\n0," + state + ",-0.12\n1," +
                                  state + ",0\n2," + state + ",-0.05\n");
  const std::string none =
      writeTemp("w_nocant.csv", "t,y,yaw,roll,V,omega,fz,curvature\n0," + state + "\n1," + state +
                                    "\n2," + state + "\n");
  const std::string canted = writeTemp("w_cant.yaml", "cant: -0.12\n");
  using Rows = std::map<std::string, std::vector<std::string>>;  // "t wheel patch" -> the row
  const auto run = [&](const std::string& scenario, bool config) {
    std::vector<std::string> args = {"wheelset", "--wheel-profile", kWheel,   "--rail-profile",
                                     kRail,      "--scenario",      scenario, "--model",
                                     "steady"};
    if (config) args.insert(args.end(), {"--config", canted});
    const CliResult r = cli(args);
    EXPECT_EQ(r.code, 0) << r.err;
    Rows rows;
    std::istringstream in(r.out);
    for (const auto& row : csvRows(in))
      if (row.size() == 19u) rows[row[0] + " " + row[1] + " " + row[2]] = row;
    return rows;
  };
  // The row without its t; or its creepages xi, eta, phi alone.
  const auto whole = [](const Rows& r, const std::string& key) {
    const std::vector<std::string>& v = r.at(key);
    return std::vector<std::string>(v.begin() + 1, v.end());
  };
  const auto creepages = [](const Rows& r, const std::string& key) {
    const std::vector<std::string>& v = r.at(key);
    return std::vector<std::string>(v.begin() + 8, v.begin() + 11);
  };
  const Rows byColumn = run(column, false), byConfig = run(none, true), level = run(none, false);
  const Rows byColumnWithConfig = run(column, true);
  ASSERT_GT(level.count("0 right gauge_corner"), 0u) << "no gauge corner patch";
  int compared = 0;
  for (const char* wheel : {"left", "right"})
    for (const char* patch : {"tread", "gauge_corner"}) {
      const std::string at = std::string(" ") + wheel + " " + patch;
      if (level.count("0" + at) == 0) continue;
      ++compared;
      EXPECT_EQ(whole(byColumn, "0" + at), whole(byConfig, "0" + at)) << at;          // -0.12 both
      EXPECT_EQ(whole(byColumn, "1" + at), whole(level, "1" + at)) << at;             // 0 both
      EXPECT_EQ(whole(byColumnWithConfig, "1" + at), whole(level, "1" + at)) << at;   // the column
      EXPECT_EQ(creepages(byConfig, "1" + at), creepages(byConfig, "0" + at)) << at;  // every row
      EXPECT_EQ(creepages(byConfig, "2" + at), creepages(byConfig, "0" + at)) << at;
    }
  EXPECT_GE(compared, 2);  // the left tread and the right gauge corner at least
  // The cant moves the gauge corner's spin (its normal leans: kappa sin(cant) n_y).
  EXPECT_NE(creepages(byColumn, "0 right gauge_corner")[2],
            creepages(level, "0 right gauge_corner")[2]);
  EXPECT_NE(creepages(byColumn, "2 right gauge_corner")[2],
            creepages(byColumn, "0 right gauge_corner")[2]);
}

TEST(ContactCliWheelset, TheShippedA22SceneIsTheBenchmarksStates) {
  // scenes/manchester_a22.csv, the docs' example, holds the same states as the test's own mapping.
  std::vector<double> y_mm;
  std::ifstream made(a22Scenario(&y_mm));
  std::ifstream shipped(std::string(WRC_SOURCE_DIR) + "/scenes/manchester_a22.csv");
  const auto a = readWheelsetScenario(made, "made"), b = readWheelsetScenario(shipped, "shipped");
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].t, b[k].t);
    for (auto m : {&WheelsetScenarioRow::y, &WheelsetScenarioRow::yaw, &WheelsetScenarioRow::roll,
                   &WheelsetScenarioRow::V, &WheelsetScenarioRow::omega,
                   &WheelsetScenarioRow::fz_left, &WheelsetScenarioRow::fz_right})
      EXPECT_NEAR(a[k].*m, b[k].*m, 1e-12 * std::max(1.0, std::abs(b[k].*m))) << k;
  }
}

TEST(ContactCliWheelset, TextProfilesTakeTheirUnitFromTheFileOrTheConfig) {
  // The benchmark's profiles written as plain text in mm, in the files' own axes, without a unit:
  // refused until --config gives profile_length_unit, then the same answer as the Simpack files.
  const auto text = [](const Profile& p) {
    std::ostringstream s;
    s.precision(17);
    for (const Eigen::Vector2d& q : p.points()) {
      const Eigen::Vector2d f = p.toFile(q) * 1e3;
      s << f.x() << "," << f.y() << "\n";
    }
    return s.str();
  };
  const std::string wheel = writeTemp("w_wheel.csv", text(*Profile::standardWheel()));
  const std::string rail = writeTemp("w_rail_mm.csv", text(*Profile::standardRail()));
  const std::string scenario = writeTemp(
      "w_one.csv", "t,y,yaw,roll,V,omega,fz\n0,-0.0005,-0.0012,-2.304e-05,2,4.34741,1e4\n");
  CliResult r = cli({"wheelset", "--wheel-profile", wheel, "--rail-profile", rail, "--scenario",
                     scenario, "--model", "steady"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no length unit"), std::string::npos) << r.err;
  const std::string config = writeTemp("w_mm.yaml", "profile_length_unit: mm\n");
  r = cli({"wheelset", "--wheel-profile", wheel, "--rail-profile", rail, "--scenario", scenario,
           "--model", "steady", "--config", config});
  ASSERT_EQ(r.code, 0) << r.err;
  const CliResult simpack = cli({"wheelset", "--wheel-profile", kWheel, "--rail-profile", kRail,
                                 "--scenario", scenario, "--model", "steady"});
  ASSERT_EQ(simpack.code, 0) << simpack.err;
  std::istringstream a(r.out), b(simpack.out);
  const auto ra = csvRows(a), rb = csvRows(b);
  ASSERT_EQ(ra.size(), rb.size());
  for (size_t k = 1; k < ra.size(); ++k) {
    EXPECT_EQ(ra[k][2], rb[k][2]);
    EXPECT_NEAR(std::stod(ra[k][3]), std::stod(rb[k][3]), 1e-6);          // y_rail
    EXPECT_NEAR(std::stod(ra[k][11]), std::stod(rb[k][11]), 1e-3 * 1e4);  // fn
  }
}
