#include "wheel_rail_contact/chi_table.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef WRC_DEFAULT_CHI_TABLE
#define WRC_DEFAULT_CHI_TABLE "config/chi_table.csv"
#endif

namespace wheel_rail_contact {

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& why) {
  throw std::runtime_error("chi table " + path + ":" + std::to_string(line) + ": " + why);
}

int kindIndex(const std::string& s) {
  if (s == "11") return 0;
  if (s == "22") return 1;
  if (s == "23") return 2;
  return -1;
}

}  // namespace

std::string ChiTable::defaultPath() {
  return WRC_DEFAULT_CHI_TABLE;
}

ChiTable ChiTable::uniform(const ChiParameters& chi) {
  return uniformSecondOrder(SecondOrderChi::fromFirstOrder(chi));
}

ChiTable ChiTable::uniformSecondOrder(const SecondOrderChi& chi) {
  ChiTable t;
  for (auto& rows : t.rows_) rows.push_back({0.0, chi});
  return t;
}

ChiTable ChiTable::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("chi table " + path + ": cannot open");
  ChiTable t;
  std::string line;
  long n = 0;
  bool header = false, second = false;  // second: the header names chi4,chi5 after chi3
  std::string lastAB[3];                // per kind, as written
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("a_over_b,kind,chi1,chi2,chi3", 0) != 0)
        fail(path, n, "expected header a_over_b,kind,chi1,chi2,chi3");
      header = true;
      second = line.rfind("a_over_b,kind,chi1,chi2,chi3,chi4,chi5", 0) == 0;
      continue;
    }
    std::stringstream ss(line);
    std::vector<std::string> f;
    for (std::string s; std::getline(ss, s, ',');) f.push_back(s);
    const std::size_t needed = second ? 7 : 5;
    if (f.size() < needed)  // more columns (fit errors) are allowed and ignored
      fail(path, n,
           "expected " + std::to_string(needed) + " or more fields (a_over_b,kind,chi1,chi2,chi3" +
               (second ? ",chi4,chi5" : "") + "), got " + std::to_string(f.size()));
    double v[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int k : {0, 2, 3, 4, 5, 6}) {
      if (k >= static_cast<int>(needed)) break;
      char* end = nullptr;
      v[k] = std::strtod(f[k].c_str(), &end);
      if (f[k].empty() || *end != '\0' || !std::isfinite(v[k]))
        fail(path, n, "field " + std::to_string(k + 1) + " is not a finite number");
    }
    const int kind = kindIndex(f[1]);
    if (kind < 0) fail(path, n, "kind must be 11, 22 or 23, got '" + f[1] + "'");
    if (!(v[0] > 0.0)) fail(path, n, "a_over_b must be > 0");
    const SecondOrderChi chi{v[2], v[3], v[4], v[5], v[6]};
    if (chi.chi4 == 0.0 && chi.chi5 == 0.0) {
      if (!ChiParameters{chi.chi1, chi.chi2, chi.chi3}.valid())
        fail(path, n, "chi3 must be > 0 (stable filter)");
    } else if (!chi.valid()) {
      fail(path, n,
           "kind " + f[1] + " at a/b = " + f[0] +
               ": second-order chi fail SecondOrderChi::valid() (unstable node for some step)");
    }
    // Interpolation needs a/b increasing; a row out of order is more likely a slip than intended.
    if (!t.rows_[kind].empty() && !(std::log(v[0]) > t.rows_[kind].back().logAB))
      fail(path, n,
           "a_over_b must increase within kind " + f[1] + ", got " + f[0] + " after " +
               lastAB[kind]);
    t.rows_[kind].push_back({std::log(v[0]), chi});
    lastAB[kind] = f[0];
  }
  if (in.bad()) fail(path, n, "read error (a directory?)");
  if (!header) fail(path, n, "empty: no header a_over_b,kind,chi1,chi2,chi3");
  for (int k = 0; k < 3; ++k) {
    if (t.rows_[k].empty())
      fail(path, n, "no rows for kind " + std::string(k == 0 ? "11" : k == 1 ? "22" : "23"));
  }
  return t;
}

ChiParameters ChiTable::at(CreepageKind kind, double a_over_b) const {
  const SecondOrderChi c = secondOrderAt(kind, a_over_b);
  return {c.chi1, c.chi2, c.chi3};
}

SecondOrderChi ChiTable::secondOrderAt(CreepageKind kind, double a_over_b) const {
  const auto& r = rows_[static_cast<int>(kind)];
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
