#include "wheel_rail_contact/shipped_tables.hpp"

#include <map>
#include <stdexcept>

namespace wheel_rail_contact {

namespace detail {
// Generated at build time from config/*.csv (cmake/shipped_tables.cmake).
const std::map<std::string, std::string_view>& shippedTableTexts();
}  // namespace detail

std::string_view shippedTable(const std::string& name) {
  const auto& tables = detail::shippedTableTexts();
  const auto it = tables.find(name);
  if (it == tables.end()) {
    std::string known;
    for (const auto& t : tables) known += (known.empty() ? "" : ", ") + t.first;
    throw std::invalid_argument("no shipped table '" + name + "' (shipped: " + known + ")");
  }
  return it->second;
}

std::vector<std::string> shippedTableNames() {
  std::vector<std::string> names;
  for (const auto& t : detail::shippedTableTexts()) names.push_back(t.first);
  return names;
}

}  // namespace wheel_rail_contact
