// The calibration table's binary format (calibration_binary.hpp): reading, lazily per mesh for the
// shipped table, writing, and the CSV dump.
#include "core/calibration/calibration_binary.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "core/fastsim/nearest_mesh.hpp"

namespace wheel_rail_contact {

namespace {

using namespace calibration;

// What the format's header names as its schema: the kinds' and multipliers' codes in the order
// the blocks hold them. A file made for another order (or other kinds) is refused.
std::string schemaText() {
  std::string s = "kinds";
  for (int k = 0; k < kKinds; ++k) (s += k == 0 ? " " : ",") += kKindInfo[k].code;
  s += "; multipliers";
  for (int p = 0; p < kMultipliers; ++p) (s += p == 0 ? " " : ",") += kMultiplierInfo[p].code;
  return s;
}

std::uint32_t fnv1a(std::string_view bytes) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : bytes) h = (h ^ c) * 16777619u;
  return h;
}

// Counts in a block are at most this (a corrupt count must not allocate gigabytes).
constexpr std::uint32_t kMaxCount = 100000;

// Little-endian reads from a block, each checked against its end.
class Reader {
 public:
  Reader(std::string_view bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {}
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("calibration table " + where_ + ": " + why);
  }
  void need(std::uint64_t words) const {
    if (words * 4 > bytes_.size() - at_) fail("truncated (a count or size does not match)");
  }
  std::uint32_t u32() {
    need(1);
    const auto* p = reinterpret_cast<const unsigned char*>(bytes_.data() + at_);
    at_ += 4;
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
           std::uint32_t(p[3]) << 24;
  }
  std::int32_t i32() {
    const std::uint32_t u = u32();
    std::int32_t v;
    std::memcpy(&v, &u, sizeof v);
    return v;
  }
  std::uint32_t count(const char* what) {
    const std::uint32_t n = u32();
    if (n > kMaxCount) fail(std::string(what) + ": count " + std::to_string(n) + " too large");
    return n;
  }
  // A value: the integer over the scale (the double strtod gives for its 6-decimal text).
  double value() { return double(i32()) / kBinaryScale; }
  std::vector<double> values(std::uint32_t n) {
    need(n);
    std::vector<double> v(n);
    for (double& x : v) x = value();
    return v;
  }
  std::string_view bytes(std::size_t n) {
    if (n > bytes_.size() - at_) fail("truncated header");
    const std::string_view b = bytes_.substr(at_, n);
    at_ += n;
    return b;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
  std::string where_;
};

class Writer {
 public:
  void u32(std::uint32_t v) {
    const char b[4] = {char(v & 255), char(v >> 8 & 255), char(v >> 16 & 255), char(v >> 24)};
    out.append(b, 4);
  }
  void i32(std::int32_t v) {
    std::uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    u32(u);
  }
  // v as millionths; refused where that is not v itself (the format would change the table).
  void value(double v) {
    const double scaled = v * kBinaryScale;
    if (!(std::abs(scaled) < 2147483647.0))
      throw std::runtime_error("calibration table: " + std::to_string(v) +
                               " is beyond the binary format's range (+-2147)");
    const std::int32_t i = static_cast<std::int32_t>(std::llround(scaled));
    if (double(i) / kBinaryScale != v) {
      char text[64];
      std::snprintf(text, sizeof text, "%.17g", v);
      throw std::runtime_error(std::string("calibration table: ") + text +
                               " is not a multiple of 1e-6 (the binary format holds 6 decimals)");
    }
    i32(i);
  }
  void values(const std::vector<double>& v) {
    for (double x : v) value(x);
  }
  std::string out;
};

bool increasing(const std::vector<double>& x) {
  for (std::size_t i = 1; i < x.size(); ++i)
    if (!(x[i] > x[i - 1])) return false;
  return true;
}

// A number as the shortest decimal of at most 6 places that reads back as it (the binary format's
// values are such numbers).
std::string decimal(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", v);
  std::string s = text;
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

}  // namespace

struct CalibrationTable::Binary {
  std::string owned;       // the bytes, where read from a file
  std::string_view bytes;  // owned's, or the library's
  std::string source;
  struct Block {
    int nx;
    std::uint32_t checksum;
    std::string_view bytes;
  };
  std::vector<Block> blocks;
  mutable std::unique_ptr<std::once_flag[]> once;
  mutable std::vector<std::vector<Row>> rows;
};

const std::vector<CalibrationTable::Row>& CalibrationTable::rowsOf(const Mesh& m) const {
  if (!binary_) return m.rows;
  const std::size_t i = static_cast<std::size_t>(&m - meshes_.data());
  const Binary& b = *binary_;
  std::call_once(b.once[i], [&] {
    b.rows[i] = readMesh(b.blocks[i].bytes, b.blocks[i].checksum, b.source, m.nx);
  });
  return b.rows[i];
}

std::vector<CalibrationTable::Row> CalibrationTable::readMesh(std::string_view block,
                                                              std::uint32_t checksum,
                                                              const std::string& source, int nx) {
  Reader in(block, source + (nx > 0 ? " (fastsim_nx " + std::to_string(nx) + ")" : ""));
  if (fnv1a(block) != checksum) in.fail("the block does not match its checksum");
  // The grids: a/b rows, each kind's knots, the correction's directions and knots.
  const std::uint32_t nRows = in.count("a/b rows");
  if (nRows == 0) in.fail("no a/b rows");
  const std::vector<double> ab = in.values(nRows);
  for (double g : ab)
    if (!(g > 0.0)) in.fail("a_over_b must be > 0");
  if (!increasing(ab)) in.fail("a_over_b must increase");
  std::vector<double> eps[kKinds];
  for (int k = 0; k < kKinds; ++k) {
    eps[k] = in.values(in.count("knots"));
    if (k <= kSpinRatio && eps[k].empty()) in.fail("every a/b must hold kinds 11, 22 and 23");
    if (!eps[k].empty() && (eps[k][0] != 0.0 || !increasing(eps[k])))
      in.fail("the knots of kind " + std::string(kKindInfo[k].code) +
              " must start at epsilon 0 and increase");
  }
  const bool noSpinSet = !eps[kEtaRatioNoSpin].empty() || !eps[kEtaCouplingNoSpin].empty() ||
                         !eps[kEtaBoundShapeNoSpin].empty();
  if (noSpinSet && (eps[kEtaRatioNoSpin].empty() || eps[kEtaCouplingNoSpin].empty() ||
                    eps[kEtaBoundShapeNoSpin].empty() || eps[kEtaCoupling].empty()))
    in.fail("22n, 22cn and 22s come together, with 22c");
  const std::uint32_t nS = in.count("spin shares"), nT = in.count("xi shares"),
                      nE = in.count("correction knots");
  const std::vector<double> s3 = in.values(nS), t = in.values(nT), corrEps = in.values(nE);
  if (nS == 0 && (nT != 0 || nE != 0)) in.fail("a correction without spin shares");
  if (nS > 0) {
    for (double s : s3)
      if (!(s > 0.0 && s < 1.0)) in.fail("spin_share must be in (0, 1)");
    if (!increasing(s3)) in.fail("the spin shares must increase");
    if (nT < 2 || t.front() != 0.0 || t.back() != 1.0 || !increasing(t))
      in.fail("the combined correction's xi shares must run from 0 to 1");
    if (nE < 2 || corrEps[0] != 0.0 || !increasing(corrEps))
      in.fail("the combined correction's knots (at least two) must start at 0 and increase");
  }
  // The values, row by row.
  const std::uint64_t nCorr = std::uint64_t(kMultipliers) * 2 * nS * nT * nE;
  std::vector<Row> rows(nRows);
  for (std::uint32_t r = 0; r < nRows; ++r) {
    Row& row = rows[r];
    row.aOverB = ab[r];
    row.logAB = std::log(ab[r]);
    for (int k = 0; k < kKinds; ++k) {
      const KindInfo& info = kKindInfo[k];
      row.eps[k] = eps[k];
      row.ratio[k] = in.values(static_cast<std::uint32_t>(eps[k].size()));
      for (double v : row.ratio[k])
        if (info.heldAsIs ? !(v >= info.min && v <= info.max) : !(v > 0.0 && v <= info.max))
          in.fail("kind " + std::string(info.code) + ": " + decimal(v) + " out of its range");
      if (info.oneAtZero && !row.ratio[k].empty() && row.ratio[k][0] != 1.0)
        in.fail("kind " + std::string(info.code) + ": ratio 1 at epsilon 0");
    }
    row.corrS3 = s3;
    row.corrT = t;
    row.corrEps = corrEps;
    in.need(nCorr);
    const std::vector<double> corr = in.values(static_cast<std::uint32_t>(nCorr));
    for (std::size_t i = 0; i < corr.size(); ++i) {
      if (!(corr[i] > 0.0 && corr[i] <= kMultiplierInfo[0].max))
        in.fail("a correction's multiplier must be > 0");
      if (i % nE == 0 && corr[i] != 1.0) in.fail("a correction's multiplier is 1 at e = 0");
    }
    row.corr = std::make_shared<const std::vector<double>>(corr);
  }
  if (!in.done()) in.fail("the block is longer than its grids say");
  return rows;
}

CalibrationTable CalibrationTable::readBinary(std::string_view bytes, const std::string& source,
                                              bool lazy) {
  auto binary = std::make_shared<Binary>();
  binary->bytes = bytes;
  binary->source = source;
  Reader in(bytes, source);
  if (bytes.substr(0, kBinaryMagic.size()) != kBinaryMagic)
    in.fail("not a calibration table (no magic " + std::string(kBinaryMagic) + ")");
  in.bytes(kBinaryMagic.size());
  const std::uint32_t version = in.u32();
  if (version != kBinaryVersion)
    in.fail("format version " + std::to_string(version) + ", this library reads version " +
            std::to_string(kBinaryVersion));
  if (in.i32() != kBinaryScale) in.fail("values not in millionths");
  const std::uint32_t schemaSize = in.count("schema");
  const std::string_view schema = in.bytes(schemaSize);
  if (schema != schemaText())
    in.fail("schema '" + std::string(schema) + "', this library reads '" + schemaText() + "'");
  const std::uint32_t nMeshes = in.count("meshes");
  if (nMeshes == 0) in.fail("no mesh");
  CalibrationTable t;
  for (std::uint32_t m = 0; m < nMeshes; ++m) {
    const int nx = in.i32();
    const std::uint32_t offset = in.u32(), size = in.u32(), checksum = in.u32();
    if (!(nx >= 2 || (nx == 0 && nMeshes == 1)))
      in.fail("fastsim_nx must be an integer >= 2 (0: one mesh for every nx)");
    if (!t.meshes_.empty() && !(nx > t.meshes_.back().nx))
      in.fail("the meshes must come in increasing fastsim_nx");
    if (offset > bytes.size() || size > bytes.size() - offset)
      in.fail("mesh " + std::to_string(nx) + "'s block lies beyond the file's end");
    binary->blocks.push_back({nx, checksum, bytes.substr(offset, size)});
    t.meshes_.push_back(Mesh{nx, {}});
  }
  // A block's checksum is checked where it is read: the shipped table's meshes one by one, as a
  // model first needs them.
  if (!lazy) {
    for (std::size_t m = 0; m < t.meshes_.size(); ++m) {
      const Binary::Block& b = binary->blocks[m];
      t.meshes_[m].rows = readMesh(b.bytes, b.checksum, source, b.nx);
    }
    return t;
  }
  binary->once = std::make_unique<std::once_flag[]>(nMeshes);
  binary->rows.resize(nMeshes);
  t.binary_ = std::move(binary);
  return t;
}

CalibrationTable CalibrationTable::fromBinary(std::string_view bytes, const std::string& source) {
  return readBinary(bytes, source, false);
}

CalibrationTable CalibrationTable::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("calibration table " + path + ": cannot open");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.compare(0, kBinaryMagic.size(), kBinaryMagic) == 0) return fromBinary(bytes, path);
  std::istringstream text(bytes);
  return parse(text, path);
}

const CalibrationTable& CalibrationTable::shipped() {
  static const CalibrationTable table =
      readBinary(shippedBinary(), "(shipped) config/calibration.bin", true);
  return table;
}

void CalibrationTable::writeBinary(std::ostream& out) const {
  const std::string schema = schemaText();
  std::vector<std::string> blocks;
  for (const Mesh& m : meshes_) {
    const std::vector<Row>& rows = rowsOf(m);
    const Row& first = rows.front();
    Writer w;
    w.u32(static_cast<std::uint32_t>(rows.size()));
    for (const Row& r : rows) w.value(r.aOverB);
    for (int k = 0; k < kKinds; ++k) {
      w.u32(static_cast<std::uint32_t>(first.eps[k].size()));
      w.values(first.eps[k]);
    }
    w.u32(static_cast<std::uint32_t>(first.corrS3.size()));
    w.u32(static_cast<std::uint32_t>(first.corrT.size()));
    w.u32(static_cast<std::uint32_t>(first.corrEps.size()));
    w.values(first.corrS3);
    w.values(first.corrT);
    w.values(first.corrEps);
    for (const Row& r : rows) {
      for (int k = 0; k < kKinds; ++k) w.values(r.ratio[k]);
      w.values(*r.corr);
    }
    blocks.push_back(std::move(w.out));
  }
  Writer h;
  h.out.append(kBinaryMagic);
  h.u32(kBinaryVersion);
  h.i32(kBinaryScale);
  h.u32(static_cast<std::uint32_t>(schema.size()));
  h.out += schema;
  h.u32(static_cast<std::uint32_t>(meshes_.size()));
  std::size_t offset = h.out.size() + meshes_.size() * 16;
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    h.i32(meshes_[m].nx);
    h.u32(static_cast<std::uint32_t>(offset));
    h.u32(static_cast<std::uint32_t>(blocks[m].size()));
    h.u32(fnv1a(blocks[m]));
    offset += blocks[m].size();
  }
  out << h.out;
  for (const std::string& b : blocks) out << b;
}

void CalibrationTable::writeCsv(std::ostream& out, int nx) const {
  bool found = false;
  for (const Mesh& m : meshes_) found = found || nx == 0 || m.nx == nx;
  if (!found) {
    std::string have;
    for (const Mesh& m : meshes_) have += (have.empty() ? "" : ", ") + std::to_string(m.nx);
    throw std::runtime_error("calibration table: no mesh " + std::to_string(nx) + " (meshes " +
                             have + ")");
  }
  const bool withNx = !meshes_.empty() && meshes_.front().nx > 0;
  out << "a_over_b,kind,epsilon,ratio" << (withNx ? ",fastsim_nx" : "")
      << ",spin_share,xi_share,sign\n";
  for (const Mesh& m : meshes_) {
    if (nx != 0 && m.nx != nx) continue;
    const std::string mesh = withNx ? "," + std::to_string(m.nx) : "";
    for (const Row& r : rowsOf(m)) {
      const std::string ab = decimal(r.aOverB);
      for (int k = 0; k < kKinds; ++k)
        for (std::size_t i = 0; i < r.eps[k].size(); ++i)
          out << ab << ',' << kKindInfo[k].name << ',' << decimal(r.eps[k][i]) << ','
              << decimal(r.ratio[k][i]) << mesh << ",,,\n";
      const std::size_t nS = r.corrS3.size(), nT = r.corrT.size(), nE = r.corrEps.size();
      for (int p = 0; p < kMultipliers; ++p)
        for (std::size_t o = 0; o < (nS > 0 ? 2 : 0); ++o)
          for (std::size_t i = 0; i < nS; ++i)
            for (std::size_t j = 0; j < nT; ++j) {
              const std::string direction = "," + decimal(r.corrS3[i]) + "," + decimal(r.corrT[j]) +
                                            "," + (o == 0 ? "1" : "-1");
              for (std::size_t k = 0; k < nE; ++k)
                out << ab << ',' << kMultiplierInfo[p].name << ',' << decimal(r.corrEps[k]) << ','
                    << decimal((*r.corr)[(((p * 2 + o) * nS + i) * nT + j) * nE + k]) << mesh
                    << direction << '\n';
            }
    }
  }
}

}  // namespace wheel_rail_contact
