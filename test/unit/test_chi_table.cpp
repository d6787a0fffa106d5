#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "wheel_rail_contact/fastsim/chi_table.hpp"

using namespace wheel_rail_contact;

namespace {
std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}
std::string loadError(const std::string& text) {
  try {
    ChiTable::load(write("bad_chi.csv", text));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
const char* kHeader = "# test\na_over_b,kind,chi1,chi2,chi3\n";
}  // namespace

TEST(ChiTable, InterpolatesInLogAOverBAndClamps) {
  const std::string path = write("chi.csv", std::string(kHeader) +
                                                "0.5,11,0.1,1.0,0.2\n2,11,0.3,1.0,0.4\n"
                                                "1,22,0.2,0.9,0.3\n1,23,0.1,0.8,0.1\n");
  const ChiTable t = ChiTable::load(path);
  EXPECT_NEAR(t.at(CreepageKind::kXi, 1.0).chi1, 0.2,
              1e-12);  // ln 1 is halfway between ln 0.5, ln 2
  EXPECT_NEAR(t.at(CreepageKind::kXi, 0.1).chi3, 0.2, 1e-12);
  EXPECT_NEAR(t.at(CreepageKind::kXi, 10).chi3, 0.4, 1e-12);
  EXPECT_NEAR(t.at(CreepageKind::kPhi, 3.0).chi2, 0.8, 1e-12);
}

TEST(ChiTable, ShippedTableLoadsAndIsStable) {
  const ChiTable shipped = ChiTable::shipped();
  EXPECT_EQ(shipped.meshes(), (std::vector<int>{5, 10, 20, 30, 40}));
  for (int nx : shipped.meshes()) {
    const ChiTable t = shipped.forMesh(nx);
    for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0})
      for (CreepageKind k : kCreepageKinds) EXPECT_GT(t.at(k, ab).chi3, 0.0) << nx;
    // Kind 23 is second order, and so is every a/b between its rows (NssModel refuses an
    // unstable interpolated F): a fine sweep in ln(a/b) over the table and beyond.
    for (double x = std::log(0.1); x <= std::log(10.0); x += 0.01) {
      const SecondOrderChi spin = t.secondOrderAt(CreepageKind::kPhi, std::exp(x));
      EXPECT_GT(spin.chi5, 0.0) << nx << " " << std::exp(x);
      EXPECT_TRUE(spin.valid()) << nx << " " << std::exp(x);
    }
  }
}

TEST(ChiTable, InterpolatesBetweenMeshesInOneOverNxAndTakesTheNearestBeyond) {
  // Meshes 10 and 40 (kinds interleaved with meshes, as a user might write them); chi1 names
  // the mesh. 1/nx halfway between 1/10 and 1/40 is nx = 16: chi1 25 there.
  auto table = [](const char* ab40) {
    std::string text = "a_over_b,kind,chi1,chi2,chi3,fastsim_nx,err_log\n";
    for (const char* kind : {"11", "22", "23"})
      for (int nx : {40, 10})
        text += std::string(nx == 40 ? ab40 : "1") + "," + kind + "," + std::to_string(nx) +
                ",1,0.5," + std::to_string(nx) + ",0\n";
    return text;
  };
  const ChiTable t = ChiTable::load(write("meshes.csv", table("1")));
  EXPECT_EQ(t.meshes(), (std::vector<int>{10, 40}));
  EXPECT_THROW(t.at(CreepageKind::kXi, 1.0), std::logic_error);  // which mesh?
  auto chi1 = [](const ChiTable& c, int nx) {
    return c.forMesh(nx).at(CreepageKind::kPhi, 1.0).chi1;
  };
  // A fitted mesh's own chi exactly, beyond the table's meshes the nearest.
  for (const auto& p : std::vector<std::pair<int, double>>{{2, 10}, {10, 10}, {40, 40}, {400, 40}})
    EXPECT_EQ(chi1(t, p.first), p.second) << p.first;
  EXPECT_NEAR(chi1(t, 16), 25.0, 1e-12);
  EXPECT_NEAR(chi1(t, 20), 10.0 + 30.0 * (0.1 - 0.05) / 0.075, 1e-12);
  EXPECT_EQ(t.forMesh(16).meshes(), (std::vector<int>{16}));
  EXPECT_EQ(t.forMesh(16).at(CreepageKind::kXi, 1.0).chi3, 0.5);
  // Meshes fitted at other a/b: the nearest (1/nx: 15 takes 10, 17 takes 40).
  const ChiTable apart = ChiTable::load(write("apart.csv", table("2")));
  EXPECT_EQ(chi1(apart, 15), 10.0);
  EXPECT_EQ(chi1(apart, 17), 40.0);
  // A table without the column serves every mesh.
  const ChiTable one = ChiTable::load(
      write("one.csv", std::string(kHeader) + "1,11,0.1,1,0.2\n1,22,0.1,1,0.2\n1,23,0.1,1,0.2\n"));
  EXPECT_EQ(one.meshes(), (std::vector<int>{0}));
  EXPECT_EQ(one.forMesh(7).at(CreepageKind::kXi, 1.0).chi1, 0.1);
}

TEST(ChiTable, MeshColumnErrorsNameTheMesh) {
  const std::string h = "a_over_b,kind,chi1,chi2,chi3,fastsim_nx\n";
  const std::string kinds10 = "1,11,0.1,1,1,10\n1,22,0.1,1,1,10\n1,23,0.1,1,1,10\n";
  EXPECT_NE(loadError(h + "1,11,0.1,1,1,1\n").find(":2: fastsim_nx must be an integer >= 2"),
            std::string::npos);
  EXPECT_NE(loadError(h + "1,11,0.1,1,1,ten\n").find("got 'ten'"), std::string::npos);
  EXPECT_NE(loadError(h + "1,11,0.1,1,1\n").find("expected 6 fields"), std::string::npos);
  EXPECT_NE(
      loadError(h + kinds10 + "1,11,0.1,1,1,20\n").find("no rows for kind 22 at fastsim_nx 20"),
      std::string::npos);
  EXPECT_NE(loadError(h + kinds10 + "0.5,11,0.1,1,1,10\n")
                .find(":5: a_over_b must increase within kind 11 at fastsim_nx 10"),
            std::string::npos);
  // The same a/b at another mesh is no repeat.
  EXPECT_EQ(loadError(h + kinds10 + "1,11,0.1,1,1,20\n1,22,0.1,1,1,20\n1,23,0.1,1,1,20\n"), "");
}

TEST(ChiTable, MalformedTablesNameFileAndLine) {
  EXPECT_NE(loadError("a,b\n").find(":1: expected header"), std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,x,1,1\n").find(":3: field 3"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,12,0,1,1\n").find("kind must be"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,0.1,1,-1\n").find("chi3 must be > 0"),
            std::string::npos);
  EXPECT_NE(loadError(std::string(kHeader) + "1,11,0.1,1,1\n").find("no rows for kind 22"),
            std::string::npos);
  EXPECT_THROW(ChiTable::load("/nonexistent/chi.csv"), std::runtime_error);
}

TEST(ChiTable, EveryMalformedTableGetsAMessageNamingTheProblem) {
  const std::string ok = "0.5,22,0.2,0.9,0.3\n0.5,23,0.1,0.8,0.1\n";
  const std::pair<std::string, std::string> cases[] = {
      {"", ":0: empty: no header"},
      {"# only a comment\n", ":1: empty: no header"},
      {"a_over_b;kind;chi1;chi2;chi3\n", ":1: expected header"},
      {std::string(kHeader), "no rows for kind 11"},
      {std::string(kHeader) + "1,11,0.1,1\n", ":3: expected 5 fields"},
      {std::string(kHeader) + "1,11,0.1,1,1,\n", ":3: expected 5 fields, as the header's columns"},
      {std::string(kHeader) + "1,11,0.1,1,1,0.2\n", "got 6"},
      {std::string(kHeader) + "1\n",
       ":3: expected 5 fields, as the header's columns (a_over_b,kind,chi1,chi2,chi3), got 1"},
      {"a_over_b,kind,chi1,chi2,chi3,max_err\n", ":1: column 'max_err' unknown or repeated"},
      {"a_over_b,kind,chi1,chi2,chi3,err_log,err_log\n",
       ":1: column 'err_log' unknown or repeated"},
      {"a_over_b,kind,chi1,chi2,chi3,\n", ":1: column '' unknown or repeated"},
      {"a_over_b,kind,chi1,chi2,chi3x\n", ":1: expected header"},
      {std::string(kHeader) + "1,11,nan,1,1\n", ":3: field 3 is not a finite number"},
      {std::string(kHeader) + "1,11,0.1,1,inf\n", ":3: field 5 is not a finite number"},
      {std::string(kHeader) + "NaN,11,0.1,1,1\n", ":3: field 1 is not a finite number"},
      {std::string(kHeader) + "1,11,0.1,1,1\r\n", ":3: field 5 is not a finite number"},
      {std::string(kHeader) + "0,11,0.1,1,1\n", ":3: a_over_b must be > 0"},
      {std::string(kHeader) + "2,11,0.1,1,1\n1,11,0.1,1,1\n" + ok,
       ":4: a_over_b must increase within kind 11, got 1 after 2"},
      {std::string(kHeader) + "1,11,0.1,1,1\n1,11,0.2,1,1\n" + ok,
       ":4: a_over_b must increase within kind 11, got 1 after 1"},
  };
  for (const auto& c : cases)
    EXPECT_NE(loadError(c.first).find(c.second), std::string::npos)
        << c.second << " <- " << loadError(c.first);
  // Kinds may interleave; only the order within a kind matters (as in the shipped table).
  EXPECT_EQ(loadError(std::string(kHeader) + "1,11,0.1,1,1\n" + ok + "2,11,0.1,1,1\n"), "");
  EXPECT_NE(loadError("a_over_b,kind,chi1,chi2,chi3\n").find("bad_chi.csv"), std::string::npos);
  try {
    ChiTable::load(::testing::TempDir());
    ADD_FAILURE() << "a directory loaded as a chi table";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("read error (a directory?)"), std::string::npos)
        << e.what();
  }
}

TEST(ChiTable, ReadsOptionalSecondOrderColumnsAndInterpolatesThem) {
  const std::string path =
      write("chi2.csv",
            "a_over_b,kind,chi1,chi2,chi3,chi4,chi5,err_log\n"
            "1,11,0.2,1.0,0.3,0,0,0.1\n1,22,0.2,0.9,0.3,0,0,0.1\n"
            "0.5,23,0.86,2.12,0.55,0.16,0.032,0.01\n2,23,0.66,1.57,0.48,0.08,0.016,0.01\n");
  const ChiTable t = ChiTable::load(path);
  const SecondOrderChi spin = t.secondOrderAt(CreepageKind::kPhi, 1.0);
  EXPECT_NEAR(spin.chi4, 0.12, 1e-12);  // halfway in ln(a/b)
  EXPECT_NEAR(spin.chi5, 0.024, 1e-12);
  EXPECT_NEAR(t.at(CreepageKind::kPhi, 1.0).chi1, 0.76, 1e-12);
  EXPECT_EQ(t.secondOrderAt(CreepageKind::kXi, 1.0).chi4, 0.0);
  // A first-order table reads as second order with chi4 = chi5 = 0.
  const ChiTable first = ChiTable::load(write(
      "chi1.csv", std::string(kHeader) + "1,11,0.1,1.0,0.2\n1,22,0.1,1,0.2\n1,23,0.1,1,0.2\n"));
  EXPECT_EQ(first.secondOrderAt(CreepageKind::kPhi, 1.0).chi5, 0.0);
  EXPECT_EQ(first.secondOrderAt(CreepageKind::kPhi, 1.0).chi3, 0.2);
}

TEST(ChiTable, RejectsAnUnstableSecondOrderRowNamingIt) {
  const std::string e = loadError(
      "a_over_b,kind,chi1,chi2,chi3,chi4,chi5\n1,11,0.2,1,0.3,0,0\n1,22,0.2,1,0.3,0,0\n"
      "1.5,23,0.1,1.0,0.1,1.0,0.01\n");  // B < 0, B^2 > 4 chi1 chi2 chi3 chi5
  EXPECT_NE(e.find(":4:"), std::string::npos) << e;
  EXPECT_NE(e.find("kind 23 at a/b = 1.5"), std::string::npos) << e;
  EXPECT_NE(loadError("a_over_b,kind,chi1,chi2,chi3,chi4,chi5\n1,11,0.2,1,0.3\n")
                .find("expected 7 fields"),
            std::string::npos);
}
