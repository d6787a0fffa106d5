/// Influence coefficients of the tangential problem for two elastically identical half-spaces
/// (shear modulus G [Pa], Poisson ratio nu) on a grid of equal rectangular elements carrying
/// piecewise-constant traction. Boussinesq-Cerruti point-force solution (Love) integrated in closed
/// form over a rectangle; the relative displacement of the two bodies is twice one body's.
/// Units: lengths m, tractions Pa, displacements m, coefficients m/Pa.
#pragma once

#include <vector>

namespace wheel_rail_contact {

/// mx x my equal elements (dx x dy) centred on the origin; element (ix, iy) has index ix * my + iy
/// and centre ((ix + 0.5 - mx/2) dx, (iy + 0.5 - my/2) dy). ix grows along the rolling direction x.
struct HalfspaceGrid {
  int mx = 0;
  int my = 0;
  double dx = 0.0;  ///< [m]
  double dy = 0.0;  ///< [m]
  double xc(int ix) const { return (ix + 0.5 - 0.5 * mx) * dx; }
  double yc(int iy) const { return (iy + 0.5 - 0.5 * my) * dy; }
  int size() const { return mx * my; }
  int index(int ix, int iy) const { return ix * my + iy; }
  /// The grid convention of CONTACT's reference runs: [-1.1a, 1.1a] x [-1.1b, 1.1b].
  static HalfspaceGrid covering(double a, double b, int mx, int my);
};

/// Relative tangential displacement at an element centre due to unit traction on an element at
/// offset (di, dj) cells: u_x = xx tau_x + xy tau_y, u_y = xy tau_x + yy tau_y. Translation
/// invariant, so one (2mx-1) x (2my-1) table serves every pair of the grid (computed once per
/// grid).
class InfluenceKernel {
 public:
  InfluenceKernel(const HalfspaceGrid& grid, double G, double nu);
  /// di = ix_field - ix_source in [-mx, mx], dj in (-my, my).
  double xx(int di, int dj) const { return xx_[at(di, dj)]; }
  double xy(int di, int dj) const { return xy_[at(di, dj)]; }
  double yy(int di, int dj) const { return yy_[at(di, dj)]; }
  const HalfspaceGrid& grid() const { return grid_; }
  /// Raw tables for tight loops: entry (di, dj) at offset(di, dj); dj + 1 is the next entry.
  int offset(int di, int dj) const { return at(di, dj); }
  const double* xxData() const { return xx_.data(); }
  const double* xyData() const { return xy_.data(); }
  const double* yyData() const { return yy_.data(); }

 private:
  int at(int di, int dj) const { return (di + grid_.mx) * (2 * grid_.my - 1) + dj + grid_.my - 1; }
  HalfspaceGrid grid_;
  std::vector<double> xx_, xy_, yy_;
};

}  // namespace wheel_rail_contact
