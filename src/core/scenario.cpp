#include "wheel_rail_contact/scenario.hpp"

#include "core/csv_fields.hpp"

#include <array>
#include <cmath>
#include <cstdlib>

namespace wheel_rail_contact {

namespace {

// The first kRequired columns must be present; a, b (together) and mu may be.
const std::array<const char*, 9> kColumns = {"t", "V", "xi", "eta", "phi", "fz", "a", "b", "mu"};
constexpr size_t kRequired = 6;

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The line's fields (splitCsvFields), each trimmed: scenarios are written by hand too.
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  splitCsvFields(line, &out);
  for (std::string& cell : out) cell = trim(cell);
  return out;
}

[[noreturn]] void fail(const std::string& source, long line, const std::string& what) {
  throw ScenarioError(source + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

StepInput stepInputAt(const std::vector<ScenarioRow>& rows, size_t k) {
  const ScenarioRow& r = rows[k];
  return {k == 0 ? 0.0 : r.t - rows[k - 1].t, r.V, r.xi, r.eta, r.phi, r.fz, r.a, r.b, r.mu};
}

std::vector<ScenarioRow> readScenario(std::istream& in, const std::string& source) {
  std::string line;
  long lineNo = 0;
  std::array<int, kColumns.size()> col{};
  col.fill(-1);
  bool haveHeader = false;
  std::size_t columns = 0;
  std::vector<ScenarioRow> rows;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto cells = splitCsv(t);
    if (!haveHeader) {
      for (size_t c = 0; c < cells.size(); ++c) {
        size_t k = 0;
        while (k < kColumns.size() && cells[c] != kColumns[k]) ++k;
        if (k == kColumns.size())
          fail(source, lineNo,
               "unknown column '" + cells[c] + "' (known: t,V,xi,eta,phi,fz and optional a,b,mu)");
        if (col[k] >= 0) fail(source, lineNo, "column '" + cells[c] + "' given twice");
        col[k] = static_cast<int>(c);
      }
      for (size_t k = 0; k < kRequired; ++k)
        if (col[k] < 0) fail(source, lineNo, std::string("missing column '") + kColumns[k] + "'");
      if ((col[6] < 0) != (col[7] < 0))
        fail(source, lineNo, "columns 'a' and 'b' must be given together");
      haveHeader = true;
      columns = cells.size();
      continue;
    }
    if (cells.size() > columns)
      fail(source, lineNo,
           std::to_string(cells.size()) + " fields, more than the header's " +
               std::to_string(columns) + " columns");
    double v[kColumns.size()] = {};
    for (size_t k = 0; k < kColumns.size(); ++k) {
      if (col[k] < 0) continue;  // an optional column not given: 0, the parameters apply
      if (col[k] >= static_cast<int>(cells.size()))
        fail(source, lineNo, std::string("field '") + kColumns[k] + "': missing value");
      const std::string& cell = cells[col[k]];
      char* end = nullptr;
      v[k] = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size())
        fail(source, lineNo,
             std::string("field '") + kColumns[k] + "': not a number ('" + cell + "')");
      if (!std::isfinite(v[k]))
        fail(source, lineNo,
             std::string("field '") + kColumns[k] + "': not finite ('" + cell + "')");
    }
    if (!rows.empty() && !(v[0] > rows.back().t))
      fail(source, lineNo, "field 't': time must increase strictly");
    rows.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]});
  }
  if (!haveHeader) fail(source, lineNo, "no header line (expected t,V,xi,eta,phi,fz)");
  return rows;
}

}  // namespace wheel_rail_contact
