#include "validation/ellipse_patch.hpp"

#include <cmath>

namespace wheel_rail_contact {

PatchShape ellipseStrips(double a, double b, double fz, int ny, double origin) {
  PatchShape s;
  s.origin = origin;
  const double p0 = 3.0 * fz / (2.0 * M_PI * a * b);
  for (int j = 0; j < ny; ++j) {
    const double yn = -1.0 + (2.0 * j + 1.0) / ny, r = std::sqrt(1.0 - yn * yn);
    s.strips.push_back(PatchStrip{b * yn, 2.0 * b / ny, a * r, -a * r, p0 * r});
  }
  return s;
}

HalfspaceGrid ellipseSlideGrid(double a, double b, double travel, int mx) {
  HalfspaceGrid g;
  g.mx = mx;
  g.dx = 2.2 * a / g.mx;
  g.dy = g.dx;
  g.my = static_cast<int>(std::ceil((2.2 * b + travel) / g.dy));
  return g;
}

Eigen::VectorXd movedEllipsePressure(const HalfspaceGrid& g, double a, double b, double fz,
                                     double s) {
  const double p0 = 3.0 * fz / (2.0 * M_PI * a * b);
  Eigen::VectorXd pressure(g.size());
  double sum = 0.0;
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = 0; iy < g.my; ++iy) {
      const double x = g.xc(ix) / a, y = (g.yc(iy) - s) / b, r = 1.0 - x * x - y * y;
      pressure(g.index(ix, iy)) = r > 0.0 ? p0 * std::sqrt(r) : 0.0;
      sum += pressure(g.index(ix, iy)) * g.dx * g.dy;
    }
  return pressure * (fz / sum);
}

}  // namespace wheel_rail_contact
