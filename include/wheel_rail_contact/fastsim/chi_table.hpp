/// Table of identified dynamic-flexibility parameters chi (nss_filter.hpp) for the creepage kinds
/// 11 (kXi), 22 (kEta), 23 (kPhi) against the semi-axis ratio a/b, interpolated linearly in ln(a/b)
/// and clamped at the table's ends, per FastSim mesh: chi absorbs the march's discretisation along
/// the strips, so it is fitted per nodes per strip nx (it hardly depends on the strips ny).
/// File format (CSV, '#' comment lines carry units, meshes and date of the fit):
///   a_over_b,kind,chi1,chi2,chi3[,chi4,chi5][,...]        with kind in {11, 22, 23}
/// chi4, chi5 (optional columns, named in the header right after chi3): the second-order F of
/// second_order_flexibility.hpp; 0 in a first-order row. A table without them is first order.
/// fastsim_nx (optional column, anywhere after chi3): the FastSim mesh's nodes per strip the row
/// was fitted at; a table without it is one mesh that serves every nx. err_log, err_linear,
/// err_max, shenli_err_log (optional, identify_chi's fit errors) are not read; any other column
/// is an error, and every row has the header's fields.
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "wheel_rail_contact/fastsim/creepage_kind.hpp"
#include "wheel_rail_contact/fastsim/nss_filter.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"

namespace wheel_rail_contact {

class ChiTable {
 public:
  /// Reads a table. Throws std::runtime_error naming the file and line on an unknown or repeated
  /// column, any malformed (not the header's field count), non-finite, unstable (chi3 <= 0) or
  /// out-of-order (a/b not increasing within its kind and mesh) entry, a fastsim_nx below 2, on a
  /// missing header (an empty file), or if a mesh lacks a kind.
  static ChiTable load(const std::string& path);
  /// The same from a stream; `source` names it in messages.
  static ChiTable parse(std::istream& in, const std::string& source);
  /// The table shipped with the package: config/chi_table.csv (meshes 5x5 to 40x40), compiled
  /// into the library (shipped_tables.hpp), so it needs no file at run time.
  static ChiTable shipped();
  /// A table with the same chi for every kind and a/b (tests; {0, 1, 0} is Shen & Li).
  static ChiTable uniform(const ChiParameters& chi);
  static ChiTable uniformSecondOrder(const SecondOrderChi& chi);

  /// The table for a FastSim mesh of nx nodes per strip, as a table of its own: between two
  /// fitted meshes their chi interpolated linearly in 1/nx (the march's step along the strip);
  /// on a fitted mesh, beyond the table's meshes, or where the two meshes differ in a/b rows or
  /// an interpolated row would be unstable, the nearest in 1/nx (a tie goes to the finer mesh).
  /// A table of one mesh is itself.
  ChiTable forMesh(int nx) const;
  /// nx of each mesh the table holds, increasing (one 0: a table without fastsim_nx).
  std::vector<int> meshes() const;

  /// The first-order part (chi1, chi2, chi3) at a/b. On a table of one mesh: narrow a table of
  /// several with forMesh() first (std::logic_error otherwise).
  ChiParameters at(CreepageKind kind, double a_over_b) const;
  /// All five chi at a/b (chi4 = chi5 = 0 for a first-order row). Interpolated like at(): the
  /// caller checks SecondOrderChi::valid() between two second-order rows.
  SecondOrderChi secondOrderAt(CreepageKind kind, double a_over_b) const;

 private:
  struct Row {
    double logAB;
    SecondOrderChi chi;
  };
  struct Mesh {
    int nx = 0;                // 0: any
    std::vector<Row> rows[3];  // per kind, sorted by a/b
  };
  std::vector<Mesh> meshes_;  // sorted by nx
  const Mesh& only() const;
};

}  // namespace wheel_rail_contact
