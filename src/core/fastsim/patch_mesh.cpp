#include "core/fastsim/patch_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wheel_rail_contact {

PatchMesh::PatchMesh(int nx, int ny, double a, double b) : nx_(nx), ny_(ny) {
  if (nx < 2) throw std::invalid_argument("nx must be >= 2");
  if (ny < 1) throw std::invalid_argument("ny must be >= 1");
  yNorm_.resize(ny);
  halfNorm_.resize(ny);
  widthNorm_.setConstant(ny, 2.0 / ny);
  for (int j = 0; j < ny; ++j) {
    yNorm_(j) = -1.0 + (2.0 * j + 1.0) / ny;
    halfNorm_(j) = std::sqrt(1.0 - yNorm_(j) * yNorm_(j));
  }
  layOut({});
  scale(a, b);
}

void PatchMesh::setStrips(int nx, const PatchShape& shape, double a, double b, StripBound bound) {
  if (nx < 2) throw std::invalid_argument("nx must be >= 2");
  if (!(a > 0.0) || !(b > 0.0)) throw std::invalid_argument("patch semi-axes must be > 0");
  int ny = 0;
  for (const PatchStrip& s : shape.strips) ny += inContact(s);
  if (ny == 0) throw std::invalid_argument("the patch has no strip in contact");
  nx_ = nx;
  ny_ = ny;
  onStrips_ = true;
  yNorm_.resize(ny);
  halfNorm_.resize(ny);
  widthNorm_.resize(ny);
  std::vector<double> factor(ny);
  double largest = 0.0;
  int j = 0;
  for (const PatchStrip& s : shape.strips) {
    if (!inContact(s)) continue;
    const double half = 0.5 * (s.x_lead - s.x_trail);
    yNorm_(j) = s.eta / b;
    halfNorm_(j) = half / a;
    widthNorm_(j) = s.width / b;
    const double amplitude = s.pmax / half;  // P_j of p = P_j sqrt(L_j^2 - x^2)
    factor[j] = bound == StripBound::kCommonCurvature ? amplitude : amplitude / half;
    largest = std::max(largest, factor[j]);
    ++j;
  }
  for (double& c : factor) c /= largest;
  layOut(factor);
  scale(a, b);
}

void PatchMesh::layOut(const std::vector<double>& shapeFactor) {
  const int nx = nx_, ny = ny_;
  xNorm_.resize(size());
  shape_.resize(size());
  shapeIntegral_ = 0.0;
  shapeSums_[0] = shapeSums_[1] = 0.0;
  double shapeSquares = 0.0;
  shapePeak_ = onStrips_ ? 0.0 : 1.0;
  for (int j = 0; j < ny; ++j) {
    double strip = 0.0;
    if (onStrips_) shapePeak_ = std::max(shapePeak_, shapeFactor[j] * halfNorm_(j) * halfNorm_(j));
    // On strips each strip's node sums weigh its width against the ellipse's 2 / ny (1 there).
    const double widthWeight = onStrips_ ? widthNorm_(j) * ny * 0.5 : 1.0;
    const double h2 = halfNorm_(j) * halfNorm_(j);
    double stripSquares = 0.0;
    for (int i = 0; i < nx; ++i) {
      const double xn = halfNorm_(j) * (1.0 - (2.0 * i + 1.0) / nx);
      xNorm_(index(i, j)) = xn;
      const double s = onStrips_ ? shapeFactor[j] * std::max(0.0, h2 - xn * xn)
                                 : std::max(0.0, 1.0 - yNorm_(j) * yNorm_(j) - xn * xn);
      shape_(index(i, j)) = s;
      strip += s;
      if (onStrips_)
        stripSquares += s * s;
      else
        shapeSquares += s * s * halfNorm_(j);
    }
    if (onStrips_) {
      shapeIntegral_ += strip * (2.0 * halfNorm_(j) / nx) * widthNorm_(j);
      shapeSums_[0] += strip * halfNorm_(j) * widthWeight;
      shapeSquares += stripSquares * halfNorm_(j) * widthWeight;
    } else {
      shapeIntegral_ += strip * (2.0 * halfNorm_(j) / nx) * (2.0 / ny);
      shapeSums_[0] += strip * halfNorm_(j);
    }
  }
  shapeSums_[1] = shapeSquares;
  inverseShapeIntegral_ = 1.0 / shapeIntegral_;
  shapeSquareRatio_ = shapeSums_[1] / shapeSums_[0];
  interior_.assign(nx, InteriorMoments{});
  for (int first = 0; first < nx; ++first)
    for (int u = nx - 3 - 2 * first; u > -(nx - 1 - 2 * first); u -= 2) {  // exact in doubles
      const double u2 = double(u) * u;
      interior_[first].count += 1.0;
      interior_[first].u2 += u2;
      interior_[first].u4 += u2 * u2;
    }
}

void PatchMesh::scale(double a, double b) {
  if (!(a > 0.0) || !(b > 0.0)) throw std::invalid_argument("patch semi-axes must be > 0");
  a_ = a;
  b_ = b;
}

}  // namespace wheel_rail_contact
