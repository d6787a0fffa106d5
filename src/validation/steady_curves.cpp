#include "validation/steady_curves.hpp"

#include "core/csv_fields.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

constexpr int kFields = 9;  // kSteadyCurvesHeader's columns

}  // namespace

std::vector<SteadyCurvePoint> readSteadyCurves(const std::string& path) {
  std::vector<SteadyCurvePoint> out;
  std::ifstream in(path);
  bool header = false;
  long n = 0;
  std::vector<std::string> f;  // the line's fields
  auto fail = [&](const std::string& why) {
    throw std::runtime_error(path + ":" + std::to_string(n) + ": " + why);
  };
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      // The columns are the cache's own, in its order: a file of other columns (a curves file of
      // --curves, say) is not read as exact points.
      if (line != kSteadyCurvesHeader)
        fail("expected the header " + std::string(kSteadyCurvesHeader) + ", not: " + line);
      header = true;
      continue;
    }
    splitCsvFields(line, &f);
    if (f.size() != kFields)
      fail(std::to_string(f.size()) + " fields, not " + std::to_string(kFields) + ": " + line);
    double v[kFields];
    for (int i = 0; i < kFields; ++i) {
      if (i == 1) continue;  // the ray's name
      char* end = nullptr;
      v[i] = std::strtod(f[i].c_str(), &end);
      if (f[i].empty() || *end != '\0' || !std::isfinite(v[i]))
        fail("not a finite number: '" + f[i] + "' in: " + line);
    }
    if (f[1].empty()) fail("no ray: " + line);
    out.push_back({v[0], f[1], v[2], Creepages{v[3], v[4], v[5]}, v[6], v[7], v[8]});
  }
  if (n > 0 && !header) fail("no header " + std::string(kSteadyCurvesHeader));
  return out;
}

}  // namespace wheel_rail_contact
