#include "core/exact/halfspace_influence.hpp"

#include <cmath>
#include <stdexcept>

namespace wheel_rail_contact {

namespace {

// x ln(y + r), r = |(x, y)|, with its limit 0 at x = 0. For y < 0, y + r cancels: use
// y + r = x^2 / (r - y) instead.
double xLogYPlusR(double x, double y) {
  if (x == 0.0) return 0.0;
  const double r = std::hypot(x, y);
  return y >= 0.0 ? x * std::log(y + r) : x * (std::log(x * x) - std::log(r - y));
}

// Primitives F with d2F/dxdy = f for the Cerruti kernels 1/r, x^2/r^3, y^2/r^3 and xy/r^3.
double pInvR(double x, double y) {
  return xLogYPlusR(x, y) + xLogYPlusR(y, x);
}
double pXX(double x, double y) {
  return xLogYPlusR(y, x);
}
double pYY(double x, double y) {
  return xLogYPlusR(x, y);
}
double pXY(double x, double y) {
  return -std::hypot(x, y);
}

// Integral of f(X - s, Y - t) over the source element [-hx, hx] x [-hy, hy] at field offset X, Y.
template <class F>
double overElement(F prim, double X, double Y, double hx, double hy) {
  return prim(X + hx, Y + hy) - prim(X - hx, Y + hy) - prim(X + hx, Y - hy) + prim(X - hx, Y - hy);
}

}  // namespace

HalfspaceGrid HalfspaceGrid::covering(double a, double b, int mx, int my) {
  if (!(a > 0.0) || !(b > 0.0) || mx < 1 || my < 1)
    throw std::invalid_argument("grid: need a, b > 0 and mx, my >= 1");
  return {mx, my, 2.2 * a / mx, 2.2 * b / my};
}

InfluenceKernel::InfluenceKernel(const HalfspaceGrid& grid, double G, double nu) : grid_(grid) {
  if (!(G > 0.0) || !(nu >= 0.0 && nu < 0.5))
    throw std::invalid_argument("influence: need G > 0 and nu in [0, 0.5)");
  const int n = (2 * grid.mx + 1) * (2 * grid.my - 1);
  xx_.resize(n);
  xy_.resize(n);
  yy_.resize(n);
  // Cerruti (Johnson 3.86 at z = 0), one body: u_x = Q/(2 pi G) ((1-nu)/r + nu x^2/r^3),
  // u_y = Q/(2 pi G) nu x y/r^3. Two identical bodies with opposite tractions: twice that.
  const double c = 2.0 / (2.0 * M_PI * G);
  const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy;
  // One quadrant, mirrored: xx and yy are even in both offsets, xy odd in both (exact symmetry
  // keeps the transient system matrix exactly symmetric).
  for (int di = 0; di <= grid.mx; ++di) {
    for (int dj = 0; dj < grid.my; ++dj) {
      const double X = di * grid.dx, Y = dj * grid.dy;
      const double i1 = overElement(pInvR, X, Y, hx, hy);
      const double xx = c * ((1.0 - nu) * i1 + nu * overElement(pXX, X, Y, hx, hy));
      const double yy = c * ((1.0 - nu) * i1 + nu * overElement(pYY, X, Y, hx, hy));
      const double xy = di == 0 || dj == 0 ? 0.0 : c * nu * overElement(pXY, X, Y, hx, hy);
      for (int sx : {-1, 1})
        for (int sy : {-1, 1}) {
          const int k = at(sx * di, sy * dj);
          xx_[k] = xx;
          yy_[k] = yy;
          xy_[k] = sx * sy * xy;
        }
    }
  }
}

}  // namespace wheel_rail_contact
