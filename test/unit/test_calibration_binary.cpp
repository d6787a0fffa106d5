// The calibration table's binary format (calibration_binary.hpp): the shipped table is the
// repository's config/calibration.bin, a table reads back from it bit for bit, its CSV dump reads
// back to the same table, and a damaged file is refused with a message, never read.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/calibration/calibration_binary.hpp"
#include "core/calibration/calibration_table.hpp"
#include "process.hpp"

using namespace wheel_rail_contact;

namespace {

// Two meshes, two a/b rows, every kind and a combined correction with c3x (values of 6 decimals,
// as the identifier writes them).
std::string everyKind() {
  std::string body = "a_over_b,kind,epsilon,ratio,fastsim_nx,spin_share,xi_share,sign\n";
  for (const char* nx : {"5", "20"})
    for (const char* ab : {"0.5", "2"}) {
      const std::string head = std::string(ab) + ",";
      const std::string tail = std::string(",") + nx + ",,,\n";
      auto kind = [&](const char* k, const char* at0, const char* at1, const char* at3) {
        body += head + k + ",0," + at0 + tail + head + k + ",1," + at1 + tail + head + k + ",3," +
                at3 + tail;
      };
      kind("11", "1", "1.012345", "1.5");
      kind("22", "1", "0.987654", "1.25");
      kind("23", "1", "1.1", std::string(nx) == "5" ? "0.8" : "0.85");
      kind("23x", "0.4", "0.55", "2.000001");
      kind("23s", "0.75", "0.75", "0.75");
      kind("22c", "-0.4", "-0.35", "0.2");
      kind("22b", "0", "-0.25", "0.5");
      kind("22n", "1", "0.9", "0.95");
      kind("22cn", "-0.3", "-0.3", "-0.1");
      kind("22s", "0.6", "0.5", "-0.5");
      for (const char* c : {"c1", "c2", "c3", "cs", "c3x"})
        for (const char* s3 : {"0.25", "0.6"})
          for (const char* t : {"0", "0.5", "1"})
            for (const char* sign : {"1", "-1"}) {
              const std::string dir =
                  std::string(",") + nx + "," + s3 + "," + t + "," + sign + "\n";
              body += head + c + ",0,1" + dir;
              body += head + c + ",2," + (std::string(sign) == "1" ? "1.234567" : "0.654321") + dir;
              body += head + c + ",5,3.5" + dir;
            }
    }
  return body;
}

CalibrationTable fromCsv(const std::string& text) {
  std::istringstream in(text);
  return CalibrationTable::parse(in, "(test)");
}

std::string binaryOf(const CalibrationTable& t) {
  std::ostringstream out;
  t.writeBinary(out);
  return out.str();
}

std::string csvOf(const CalibrationTable& t, int nx = 0) {
  std::ostringstream out;
  t.writeCsv(out, nx);
  return out.str();
}

// Every table value a model uses, through the step it takes: the same table gives the same
// steps bit for bit. Creepages of every kind, with and without spin, both signs of eta phi.
void expectSameSteps(const CalibrationTable& x, const CalibrationTable& y, int nx) {
  for (double ab : {0.2, 0.5, 1.0, 2.0, 5.0}) {
    const PatchCalibration p = x.forMesh(nx).at(ab), q = y.forMesh(nx).at(ab);
    const double a = 5e-3 * std::sqrt(ab), b = 5e-3 / std::sqrt(ab), G = 8.2e10, muFz = 3e3;
    const CreepCoefficients k = kalkerCoefficients(ab, 0.28);
    for (const Creepages c :
         {Creepages{1e-3, 0, 0}, Creepages{0, -2e-3, 0}, Creepages{0, 0, 0.5},
          Creepages{1e-3, 1e-3, 0}, Creepages{1e-3, -4e-4, 0.6}, Creepages{-3e-3, 2e-3, 1.5},
          Creepages{2e-4, 1e-3, -0.3}, Creepages{5e-2, 2e-2, 8.0}, Creepages{1e-4, 1e-3, 0.02}}) {
      const CalibratedStep s = p.step(a, b, G, k, muFz, c), t = q.step(a, b, G, k, muFz, c);
      EXPECT_EQ(s.L.L1, t.L.L1) << nx << " " << ab;
      EXPECT_EQ(s.L.L2, t.L.L2) << nx << " " << ab;
      EXPECT_EQ(s.L.L3, t.L.L3) << nx << " " << ab;
      EXPECT_EQ(s.L.spinX(), t.L.spinX()) << nx << " " << ab;
      EXPECT_EQ(s.L.lateralCoupling, t.L.lateralCoupling) << nx << " " << ab;
      EXPECT_EQ(s.L.etaSlope, t.L.etaSlope) << nx << " " << ab;
      EXPECT_EQ(s.boundShape, t.boundShape) << nx << " " << ab;
    }
  }
}

std::string readError(const std::string& bytes) {
  try {
    CalibrationTable::fromBinary(bytes, "(damaged)");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::uint32_t fnv1a(const std::string& bytes) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : bytes) h = (h ^ c) * 16777619u;
  return h;
}

std::uint32_t wordAt(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + i]);
  return v;
}

void setWord(std::string* b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) (*b)[at + i] = static_cast<char>(v >> (8 * i) & 255);
}

// Where the first mesh's directory entry (nx, offset, size, checksum) lies in a file's header:
// after the magic, version, scale, the schema's length and text, and the mesh count.
std::size_t firstEntry(const std::string& b) {
  return 8 + 4 + 4 + 4 + wordAt(b, 16) + 4;
}

}  // namespace

TEST(CalibrationBinary, TheShippedTableIsTheRepositorysFileByteForByte) {
  const std::string file =
      wrc_test::fileText(std::string(WRC_SOURCE_DIR) + "/config/calibration.bin");
  ASSERT_FALSE(file.empty());
  EXPECT_EQ(calibration::shippedBinary(), file);
  EXPECT_LE(file.size(), 3u << 20);  // issue 44: at most 3 MB
  EXPECT_EQ(CalibrationTable::shipped().meshes(), (std::vector<int>{5, 10, 20, 30, 40}));
}

TEST(CalibrationBinary, ATableReadsBackFromItBitForBit) {
  const CalibrationTable csv = fromCsv(everyKind());
  const std::string bytes = binaryOf(csv);
  const CalibrationTable bin = CalibrationTable::fromBinary(bytes, "(test)");
  EXPECT_EQ(bin.meshes(), csv.meshes());
  for (int nx : {5, 10, 20, 40}) expectSameSteps(csv, bin, nx);  // 10: between the two meshes
  EXPECT_EQ(csvOf(bin), csvOf(csv));
  EXPECT_EQ(binaryOf(bin), bytes);
  // load() tells the formats apart by the binary's magic.
  const std::string path = testing::TempDir() + "calibration_test.bin";
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(csvOf(CalibrationTable::load(path)), csvOf(csv));
}

TEST(CalibrationBinary, TheDumpOfAShippedMeshReadsBackToTheSameTable) {
  const CalibrationTable& shipped = CalibrationTable::shipped();
  const CalibrationTable dumped = fromCsv(csvOf(shipped, 20));
  EXPECT_EQ(dumped.meshes(), std::vector<int>{20});
  expectSameSteps(shipped, dumped, 20);
  EXPECT_EQ(binaryOf(dumped), binaryOf(shipped.forMesh(20)));
  // Kinds by their readable names; a mesh the table does not hold is an error naming those it
  // holds.
  EXPECT_NE(csvOf(shipped, 20).find(",eta_coupling_no_spin,"), std::string::npos);
  try {
    csvOf(shipped, 7);
    FAIL() << "mesh 7 dumped";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("meshes 5, 10, 20, 30, 40"), std::string::npos);
  }
}

TEST(CalibrationBinary, AValueTheFormatCannotHoldIsNotWritten) {
  std::string body = everyKind();
  body.replace(body.find("1.012345"), 8, "1.0123456");  // a seventh decimal
  EXPECT_THROW(binaryOf(fromCsv(body)), std::runtime_error);
  body = everyKind();
  body.replace(body.find("1.012345"), 8, "2500");  // beyond int32 millionths
  EXPECT_THROW(binaryOf(fromCsv(body)), std::runtime_error);
}

TEST(CalibrationBinary, ADamagedFileIsRefusedWithAMessage) {
  const std::string good = binaryOf(fromCsv(everyKind()));
  ASSERT_EQ(readError(good), "");
  EXPECT_NE(readError("").find("no magic"), std::string::npos);
  EXPECT_NE(readError("a_over_b,kind,epsilon,ratio\n").find("no magic"), std::string::npos);
  std::string b = good;
  setWord(&b, 8, 2);
  EXPECT_NE(readError(b).find("format version 2, this library reads version 1"), std::string::npos);
  b = good;
  b[20] = 'K';  // the schema's text: "kinds ..." -> "Kinds ..."
  EXPECT_NE(readError(b).find("this library reads 'kinds 11,22,23,23x"), std::string::npos);
  for (std::size_t cut : {good.size() - 1, good.size() / 2, firstEntry(good) + 6}) {
    EXPECT_NE(readError(good.substr(0, cut)), "") << cut;
  }
  // A byte of a block changed: its checksum.
  const std::size_t entry = firstEntry(good), offset = wordAt(good, entry + 4);
  b = good;
  b[offset + 100] ^= 1;
  EXPECT_NE(readError(b).find("(fastsim_nx 5): the block does not match its checksum"),
            std::string::npos);
  // The same with the checksum made to match: the values themselves are checked. The block's
  // first value (after the a/b rows, the knots of 10 kinds, 3 each, and the correction's grid:
  // 3 counts, 2 + 3 + 3 values) is 11's ratio at knot 0, which must be 1; 22c's any.
  const std::size_t first = offset + 4 * (1 + 2 + 10 * (1 + 3) + 3 + 2 + 3 + 3);
  ASSERT_EQ(wordAt(good, first), 1000000u);
  b = good;
  setWord(&b, first, 2000000);
  setWord(&b, entry + 12, fnv1a(b.substr(offset, wordAt(good, entry + 8))));
  EXPECT_NE(readError(b).find("kind 11: ratio 1 at epsilon 0"), std::string::npos);
  setWord(&b, first, static_cast<std::uint32_t>(-1000000));
  setWord(&b, entry + 12, fnv1a(b.substr(offset, wordAt(good, entry + 8))));
  EXPECT_NE(readError(b).find("kind 11: -1 out of its range"), std::string::npos);
  // A block's size that says more than its grids hold.
  b = good;
  setWord(&b, entry + 8, wordAt(good, entry + 8) + 4);
  EXPECT_NE(readError(b), "");
}
