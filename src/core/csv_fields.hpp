/// The one rule by which the package's CSV readers (scenarios, the chi table, the steady
/// calibration, the exact curves' cache) cut a line into fields.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace wheel_rail_contact {

/// Cuts `line` at every comma into `*fields` (resized to the field count). Nothing is trimmed or
/// unquoted; a line ending in a comma has an empty last field, so that a reader counting fields
/// against its header sees the extra one. Field std::string: copies, their buffers reused from
/// line to line; std::string_view: views into `line`, valid while it is (the 650 000-row
/// calibration table is read at start-up).
template <class Field>
inline void splitCsvFields(const std::string& line, std::vector<Field>* fields) {
  std::size_t n = 0;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(line.find(',', start), line.size());
    if (n == fields->size()) fields->emplace_back();
    if constexpr (std::is_same_v<Field, std::string_view>)
      (*fields)[n++] = std::string_view(line).substr(start, comma - start);
    else
      (*fields)[n++].assign(line, start, comma - start);
    if (comma == line.size()) break;
    start = comma + 1;
  }
  fields->resize(n);
}

}  // namespace wheel_rail_contact
