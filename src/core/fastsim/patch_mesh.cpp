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
  for (int j = 0; j < ny; ++j) {
    yNorm_(j) = -1.0 + (2.0 * j + 1.0) / ny;
    halfNorm_(j) = std::sqrt(1.0 - yNorm_(j) * yNorm_(j));
  }
  xNorm_.resize(size());
  shape_.resize(size());
  double shapeSquares = 0.0;
  for (int j = 0; j < ny; ++j) {
    double strip = 0.0;
    for (int i = 0; i < nx; ++i) {
      const double xn = halfNorm_(j) * (1.0 - (2.0 * i + 1.0) / nx);
      xNorm_(index(i, j)) = xn;
      shape_(index(i, j)) = std::max(0.0, 1.0 - yNorm_(j) * yNorm_(j) - xn * xn);
      strip += shape_(index(i, j));
      shapeSquares += shape_(index(i, j)) * shape_(index(i, j)) * halfNorm_(j);
    }
    shapeIntegral_ += strip * (2.0 * halfNorm_(j) / nx) * (2.0 / ny);
    shapeSums_[0] += strip * halfNorm_(j);
  }
  shapeSums_[1] = shapeSquares;
  inverseShapeIntegral_ = 1.0 / shapeIntegral_;
  shapeSquareRatio_ = shapeSums_[1] / shapeSums_[0];
  interior_.resize(nx);
  for (int first = 0; first < nx; ++first)
    for (int u = nx - 3 - 2 * first; u > -(nx - 1 - 2 * first); u -= 2) {  // exact in doubles
      const double u2 = double(u) * u;
      interior_[first].count += 1.0;
      interior_[first].u2 += u2;
      interior_[first].u4 += u2 * u2;
    }
  scale(a, b);
}

void PatchMesh::scale(double a, double b) {
  if (!(a > 0.0) || !(b > 0.0)) throw std::invalid_argument("patch semi-axes must be > 0");
  a_ = a;
  b_ = b;
}

}  // namespace wheel_rail_contact
