/// The one rule by which the package's CSV readers (scenarios, the chi table, the steady
/// calibration, the exact curves' cache) cut a line into fields.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace wheel_rail_contact {

/// Cuts `line` at every comma into `*fields` (resized to the field count; the strings' buffers are
/// reused from line to line, as the 330 000-row calibration table is read at start-up). Nothing is
/// trimmed or unquoted; a line ending in a comma has an empty last field, so that a reader counting
/// fields against its header sees the extra one.
inline void splitCsvFields(const std::string& line, std::vector<std::string>* fields) {
  std::size_t n = 0;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(line.find(',', start), line.size());
    if (n == fields->size()) fields->emplace_back();
    (*fields)[n++].assign(line, start, comma - start);
    if (comma == line.size()) break;
    start = comma + 1;
  }
  fields->resize(n);
}

}  // namespace wheel_rail_contact
