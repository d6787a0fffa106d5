/// Data shipped inside the library: each config/<name>.csv of the source tree (and the standard
/// profiles, config/profiles/*.prw, *.prr) is compiled
/// into the core at build time, so an installed package finds its tables wherever it is installed.
/// A user's own table is still read from a file (e.g. the chi_table parameter).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace wheel_rail_contact {

/// The text of the shipped table `name` (its file name under config/ without .csv, e.g.
/// "chi_table"; a file of another type with its extension, e.g.
/// "profiles/MBench_S1002_v3.prw"), in the
/// library's read-only data (not copied). Throws std::invalid_argument naming the shipped tables
/// for an unknown name.
std::string_view shippedTable(const std::string& name);
/// The names of the shipped tables, sorted.
std::vector<std::string> shippedTableNames();

}  // namespace wheel_rail_contact
