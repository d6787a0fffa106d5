#include "wheel_rail_contact/fastsim/chi_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/csv_fields.hpp"
#include "core/fastsim/nearest_mesh.hpp"
#include "wheel_rail_contact/shipped_tables.hpp"

namespace wheel_rail_contact {

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& why) {
  throw std::runtime_error("chi table " + path + ":" + std::to_string(line) + ": " + why);
}

int kindIndex(const std::string& s) {
  for (int k = 0; k < 3; ++k)
    if (s == coefficientCode(static_cast<CreepageKind>(k))) return k;
  return -1;
}

bool firstOrder(const SecondOrderChi& c) {
  return c.chi4 == 0.0 && c.chi5 == 0.0;
}

// A row's F stable for every step: a first-order row as ChiParameters (which also allows the
// static chi1 = chi3 = 0), a second-order one as SecondOrderChi.
bool stable(const SecondOrderChi& c) {
  return firstOrder(c) ? ChiParameters{c.chi1, c.chi2, c.chi3}.valid() : c.valid();
}

}  // namespace

ChiTable ChiTable::shipped() {
  // Parsed once per process, copied from then on: a model made as a patch appears does not parse
  // the text again.
  static const ChiTable table = [] {
    std::istringstream in{std::string(shippedTable("chi_table"))};
    return parse(in, "(shipped) chi_table.csv");
  }();
  return table;
}

ChiTable ChiTable::uniform(const ChiParameters& chi) {
  return uniformSecondOrder(SecondOrderChi::fromFirstOrder(chi));
}

ChiTable ChiTable::uniformSecondOrder(const SecondOrderChi& chi) {
  ChiTable t;
  t.meshes_.emplace_back();
  for (auto& rows : t.meshes_.back().rows) rows.push_back({0.0, chi});
  return t;
}

namespace {

// What the header says about the columns.
struct Layout {
  bool second = false;  // chi4,chi5 right after chi3
  int meshColumn = -1;  // fastsim_nx's field, if any
  std::size_t columns = 0;
};

// The columns identify_chi writes after chi3 (chi5) besides fastsim_nx: its fit errors, for the
// reader of the table, not read here.
const char* const kFitErrorColumns[] = {"err_log", "err_linear", "err_max", "shenli_err_log"};

Layout parseHeader(const std::string& path, long n, const std::string& line) {
  std::vector<std::string> f;
  splitCsvFields(line, &f);
  const char* const leading[] = {"a_over_b", "kind", "chi1", "chi2", "chi3", "chi4", "chi5"};
  Layout L;
  for (int i = 0; i < 5; ++i)
    if (f.size() <= static_cast<std::size_t>(i) || f[i] != leading[i])
      fail(path, n, "expected header a_over_b,kind,chi1,chi2,chi3");
  L.second = f.size() >= 7 && f[5] == leading[5] && f[6] == leading[6];
  for (std::size_t i = L.second ? 7 : 5; i < f.size(); ++i) {
    if (f[i] == "fastsim_nx" && L.meshColumn < 0) {
      L.meshColumn = static_cast<int>(i);
      continue;
    }
    const auto known = std::find(std::begin(kFitErrorColumns), std::end(kFitErrorColumns), f[i]);
    if (known == std::end(kFitErrorColumns) ||
        std::find(f.begin() + 5, f.begin() + i, f[i]) != f.begin() + i)
      fail(path, n,
           "column '" + f[i] +
               "' unknown or repeated (after chi3 or chi4,chi5: fastsim_nx, err_log, err_linear, "
               "err_max, shenli_err_log)");
  }
  L.columns = f.size();
  return L;
}

// One data row, checked: fields, finite numbers, kind, a/b > 0, a stable F.
struct ParsedRow {
  std::vector<std::string> f;  // the fields as written
  int nx = 0, kind = 0;
  double ab = 0.0;
  SecondOrderChi chi;
};

ParsedRow parseRow(const std::string& path, long n, const std::string& line, const Layout& L) {
  ParsedRow r;
  splitCsvFields(line, &r.f);
  const std::vector<std::string>& f = r.f;
  const int chiFields = L.second ? 7 : 5;
  if (f.size() != L.columns)
    fail(path, n,
         "expected " + std::to_string(L.columns) +
             " fields, as the header's columns (a_over_b,kind,chi1,chi2,chi3" +
             (L.second ? ",chi4,chi5" : "") +
             (L.columns > static_cast<std::size_t>(chiFields) ? ",..." : "") + "), got " +
             std::to_string(f.size()));
  double v[7] = {0, 0, 0, 0, 0, 0, 0};
  for (int k : {0, 2, 3, 4, 5, 6}) {
    if (k >= chiFields) break;
    char* end = nullptr;
    v[k] = std::strtod(f[k].c_str(), &end);
    if (f[k].empty() || *end != '\0' || !std::isfinite(v[k]))
      fail(path, n, "field " + std::to_string(k + 1) + " is not a finite number");
  }
  if (L.meshColumn > 0) {
    const std::string& m = f[L.meshColumn];
    char* end = nullptr;
    const long nx = std::strtol(m.c_str(), &end, 10);
    if (m.empty() || *end != '\0' || nx < 2 || nx > 100000)
      fail(path, n, "fastsim_nx must be an integer >= 2, got '" + m + "'");
    r.nx = static_cast<int>(nx);
  }
  r.kind = kindIndex(f[1]);
  if (r.kind < 0) fail(path, n, "kind must be 11, 22 or 23, got '" + f[1] + "'");
  r.ab = v[0];
  if (!(r.ab > 0.0)) fail(path, n, "a_over_b must be > 0");
  r.chi = {v[2], v[3], v[4], v[5], v[6]};
  if (!stable(r.chi))
    fail(path, n,
         firstOrder(r.chi) ? "chi3 must be > 0 (stable filter)"
                           : "kind " + f[1] + " at a/b = " + f[0] +
                                 ": second-order chi fail SecondOrderChi::valid() (unstable node "
                                 "for some step)");
  return r;
}

}  // namespace

ChiTable ChiTable::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("chi table " + path + ": cannot open");
  return parse(in, path);
}

ChiTable ChiTable::parse(std::istream& in, const std::string& path) {
  ChiTable t;
  std::string line;
  long n = 0;
  bool header = false;
  Layout layout;
  std::vector<std::array<std::string, 3>> lastAB;  // per mesh (as meshes_) and kind, as written
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      layout = parseHeader(path, n, line);
      header = true;
      continue;
    }
    const ParsedRow r = parseRow(path, n, line, layout);
    auto mesh = std::find_if(t.meshes_.begin(), t.meshes_.end(),
                             [&r](const Mesh& m) { return m.nx == r.nx; });
    if (mesh == t.meshes_.end()) {
      t.meshes_.push_back(Mesh{r.nx, {}});
      lastAB.emplace_back();
      mesh = t.meshes_.end() - 1;
    }
    auto& rows = mesh->rows[r.kind];
    std::string& last = lastAB[mesh - t.meshes_.begin()][r.kind];
    // Interpolation needs a/b increasing; a row out of order is more likely a slip than intended.
    if (!rows.empty() && !(std::log(r.ab) > rows.back().logAB))
      fail(path, n,
           "a_over_b must increase within kind " + r.f[1] +
               (r.nx ? " at fastsim_nx " + std::to_string(r.nx) : "") + ", got " + r.f[0] +
               " after " + last);
    rows.push_back({std::log(r.ab), r.chi});
    last = r.f[0];
  }
  if (in.bad()) fail(path, n, "read error (a directory?)");
  if (!header) fail(path, n, "empty: no header a_over_b,kind,chi1,chi2,chi3");
  if (t.meshes_.empty()) fail(path, n, "no rows for kind 11");
  for (const Mesh& m : t.meshes_)
    for (int k = 0; k < 3; ++k)
      if (m.rows[k].empty())
        fail(path, n,
             std::string("no rows for kind ") + coefficientCode(static_cast<CreepageKind>(k)) +
                 (m.nx ? " at fastsim_nx " + std::to_string(m.nx) : ""));
  sortByNodes(&t.meshes_);
  return t;
}

ChiTable ChiTable::forMesh(int nx) const {
  if (meshes_.size() <= 1) return *this;
  // Between two identified meshes each chi is interpolated in 1/nx, where both meshes hold the
  // same a/b rows and every interpolated row stays stable; else the nearest mesh.
  const Mesh *lo = nullptr, *hi = nullptr;
  double w = 0.0;
  auto interpolated = [&](Mesh* m) {
    auto mix = [w](double x, double y) { return x + w * (y - x); };
    for (int k = 0; k < 3; ++k) {
      const std::vector<Row>&a = lo->rows[k], &b = hi->rows[k];
      if (a.size() != b.size()) return false;
      for (std::size_t r = 0; r < a.size(); ++r) {
        if (a[r].logAB != b[r].logAB) return false;
        const SecondOrderChi &x = a[r].chi, &y = b[r].chi;
        const SecondOrderChi c{mix(x.chi1, y.chi1), mix(x.chi2, y.chi2), mix(x.chi3, y.chi3),
                               mix(x.chi4, y.chi4), mix(x.chi5, y.chi5)};
        if (!stable(c)) return false;
        m->rows[k].push_back({a[r].logAB, c});
      }
    }
    return true;
  };
  ChiTable t;
  Mesh m{nx, {}};
  if (meshesAround(meshes_, nx, &lo, &hi, &w) && interpolated(&m))
    t.meshes_.push_back(std::move(m));
  else
    t.meshes_.push_back(nearestMesh(meshes_, nx));
  return t;
}

std::vector<int> ChiTable::meshes() const {
  return nodeCounts(meshes_);
}

const ChiTable::Mesh& ChiTable::only() const {
  if (meshes_.size() != 1)
    throw std::logic_error("ChiTable: a table of " + std::to_string(meshes_.size()) +
                           " FastSim meshes: narrow it with forMesh() first");
  return meshes_.front();
}

ChiParameters ChiTable::at(CreepageKind kind, double a_over_b) const {
  const SecondOrderChi c = secondOrderAt(kind, a_over_b);
  return {c.chi1, c.chi2, c.chi3};
}

SecondOrderChi ChiTable::secondOrderAt(CreepageKind kind, double a_over_b) const {
  const auto& r = only().rows[static_cast<int>(kind)];
  const double x = std::log(a_over_b);
  if (r.size() == 1 || x <= r.front().logAB) return r.front().chi;
  if (x >= r.back().logAB) return r.back().chi;
  const auto hi = std::upper_bound(r.begin(), r.end(), x,
                                   [](double v, const Row& row) { return v < row.logAB; });
  const auto lo = hi - 1;
  const double w = (x - lo->logAB) / (hi->logAB - lo->logAB);
  auto mix = [w](double u, double v) { return (1 - w) * u + w * v; };
  const SecondOrderChi &l = lo->chi, &h = hi->chi;
  return {mix(l.chi1, h.chi1), mix(l.chi2, h.chi2), mix(l.chi3, h.chi3), mix(l.chi4, h.chi4),
          mix(l.chi5, h.chi5)};
}

}  // namespace wheel_rail_contact
