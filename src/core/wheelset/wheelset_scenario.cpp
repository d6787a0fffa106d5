#include "wheel_rail_contact/wheelset/wheelset_scenario.hpp"

#include "core/csv_fields.hpp"

#include <array>
#include <cmath>
#include <cstdlib>

namespace wheel_rail_contact {

namespace {

enum Column {
  kT,
  kY,
  kYaw,
  kRoll,
  kV,
  kOmega,
  kFz,
  kFzLeft,
  kFzRight,
  kVy,
  kYawRate,
  kCurvature,
  kCant,
  kVz,
  kRollRate
};
const std::array<const char*, 15> kNames = {
    "t",        "y",  "yaw",      "roll",      "V",    "omega", "fz",       "fz_left",
    "fz_right", "vy", "yaw_rate", "curvature", "cant", "vz",    "roll_rate"};
const char* const kKnown =
    "t,y,yaw,roll,V,omega and fz or fz_left,fz_right; optional "
    "vy,yaw_rate,curvature,cant,vz,roll_rate";

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

[[noreturn]] void fail(const std::string& source, long line, const std::string& what) {
  throw WheelsetScenarioError(source + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

std::vector<WheelsetScenarioRow> readWheelsetScenario(std::istream& in, const std::string& source) {
  std::string line;
  long lineNo = 0;
  std::array<int, kNames.size()> col{};
  col.fill(-1);
  bool haveHeader = false;
  std::size_t columns = 0;
  std::vector<std::string> cells;
  std::vector<WheelsetScenarioRow> rows;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;
    splitCsvFields(text, &cells);
    for (std::string& cell : cells) cell = trim(cell);
    if (!haveHeader) {
      for (size_t c = 0; c < cells.size(); ++c) {
        size_t k = 0;
        while (k < kNames.size() && cells[c] != kNames[k]) ++k;
        if (k == kNames.size())
          fail(source, lineNo, "unknown column '" + cells[c] + "' (known: " + kKnown + ")");
        if (col[k] >= 0) fail(source, lineNo, "column '" + cells[c] + "' given twice");
        col[k] = static_cast<int>(c);
      }
      for (int k : {kT, kY, kYaw, kRoll, kV, kOmega})
        if (col[k] < 0) fail(source, lineNo, std::string("missing column '") + kNames[k] + "'");
      const bool pair = col[kFzLeft] >= 0 || col[kFzRight] >= 0;
      if (col[kFz] >= 0 && pair)
        fail(source, lineNo,
             "columns 'fz' and 'fz_left','fz_right' given together: one or the other");
      if (pair && (col[kFzLeft] < 0 || col[kFzRight] < 0))
        fail(source, lineNo, "columns 'fz_left' and 'fz_right' must be given together");
      if (col[kFz] < 0 && !pair) fail(source, lineNo, "missing column 'fz' (or fz_left,fz_right)");
      haveHeader = true;
      columns = cells.size();
      continue;
    }
    if (cells.size() != columns)
      fail(source, lineNo,
           std::to_string(cells.size()) + " fields, the header has " + std::to_string(columns) +
               " columns");
    double v[kNames.size()] = {};
    for (size_t k = 0; k < kNames.size(); ++k) {
      if (col[k] < 0) continue;  // an optional column not given: 0
      const std::string& cell = cells[col[k]];
      char* end = nullptr;
      v[k] = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size())
        fail(source, lineNo,
             std::string("field '") + kNames[k] + "': not a number ('" + cell + "')");
      if (!std::isfinite(v[k]))
        fail(source, lineNo, std::string("field '") + kNames[k] + "': not finite ('" + cell + "')");
    }
    if (!rows.empty() && !(v[kT] > rows.back().t))
      fail(source, lineNo, "field 't': time must increase strictly");
    WheelsetScenarioRow r;
    r.t = v[kT];
    r.y = v[kY];
    r.yaw = v[kYaw];
    r.roll = v[kRoll];
    r.V = v[kV];
    r.omega = v[kOmega];
    r.fz_left = col[kFz] >= 0 ? v[kFz] : v[kFzLeft];
    r.fz_right = col[kFz] >= 0 ? v[kFz] : v[kFzRight];
    r.vy = v[kVy];
    r.yaw_rate = v[kYawRate];
    r.curvature = v[kCurvature];
    if (col[kCant] >= 0) r.cant = v[kCant];
    r.vz = v[kVz];
    r.roll_rate = v[kRollRate];
    rows.push_back(r);
  }
  if (!haveHeader) fail(source, lineNo, "no header line (expected t,y,yaw,roll,V,omega,fz)");
  return rows;
}

}  // namespace wheel_rail_contact
