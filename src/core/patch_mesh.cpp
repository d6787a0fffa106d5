#include "wheel_rail_contact/patch_mesh.hpp"

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
  scale(a, b);
}

void PatchMesh::scale(double a, double b) {
  if (!(a > 0.0) || !(b > 0.0)) throw std::invalid_argument("patch semi-axes must be > 0");
  a_ = a;
  b_ = b;
}

}  // namespace wheel_rail_contact
