/// Table of identified dynamic-flexibility parameters chi (nss_filter.hpp) for the creepage kinds
/// 11 (kXi), 22 (kEta), 23 (kPhi) against the semi-axis ratio a/b, interpolated linearly in ln(a/b)
/// and clamped at the table's ends.
/// File format (CSV, '#' comment lines carry units, mesh and date of the fit):
///   a_over_b,kind,chi1,chi2,chi3[,chi4,chi5][,...]        with kind in {11, 22, 23}
/// chi4, chi5 (optional columns, named in the header right after chi3): the second-order F of
/// second_order_flexibility.hpp; 0 in a first-order row. A table without them is first order.
#pragma once

#include <string>
#include <vector>

#include "wheel_rail_contact/creepage_kind.hpp"
#include "wheel_rail_contact/nss_filter.hpp"
#include "wheel_rail_contact/second_order_flexibility.hpp"

namespace wheel_rail_contact {

class ChiTable {
 public:
  /// Reads a table. Throws std::runtime_error naming the file and line on any malformed (fewer
  /// than 5 fields), non-finite, unstable (chi3 <= 0) or out-of-order (a/b not increasing within
  /// its kind) entry, on a missing header (an empty file), or if a kind is missing.
  static ChiTable load(const std::string& path);
  /// The table shipped with the package (config/chi_table.csv).
  static std::string defaultPath();
  /// A table with the same chi for every kind and a/b (tests; {0, 1, 0} is Shen & Li).
  static ChiTable uniform(const ChiParameters& chi);
  static ChiTable uniformSecondOrder(const SecondOrderChi& chi);

  /// The first-order part (chi1, chi2, chi3) at a/b.
  ChiParameters at(CreepageKind kind, double a_over_b) const;
  /// All five chi at a/b (chi4 = chi5 = 0 for a first-order row). Interpolated like at(): the
  /// caller checks SecondOrderChi::valid() between two second-order rows.
  SecondOrderChi secondOrderAt(CreepageKind kind, double a_over_b) const;

 private:
  struct Row {
    double logAB;
    SecondOrderChi chi;
  };
  std::vector<Row> rows_[3];  // per kind, sorted by a/b
};

}  // namespace wheel_rail_contact
