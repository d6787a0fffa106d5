#include "wheel_rail_contact/fastsim.hpp"

#include <cmath>

namespace wheel_rail_contact {

Flexibilities kalkerFlexibilities(double a, double b, double G, const CreepCoefficients& c) {
  Flexibilities L;
  L.L1 = 8.0 * a / (3.0 * c.c11 * G);
  L.L2 = 8.0 * a / (3.0 * c.c22 * G);
  L.L3 = M_PI * a * std::sqrt(a / b) / (4.0 * c.c23 * G);
  return L;
}

void TractionField::resize(int n) {
  tx.setZero(n);
  ty.setZero(n);
  bound.setZero(n);
  slip.setConstant(n, false);
}

void parabolicBound(const PatchMesh& mesh, double a, double b, double fz, double mu,
                    Eigen::ArrayXd* bound) {
  if (a == mesh.a() && b == mesh.b()) {  // the patch fills the mesh: precomputed shape
    *bound = mesh.pressureShape() * (mu * fz / (mesh.shapeIntegral() * a * b));
    return;
  }
  bound->resize(mesh.size());
  const double ka = mesh.a() / a;
  double sum = 0.0;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double y = mesh.stripY(j);
    const double ry = 1.0 - y * y / (b * b);
    double strip = 0.0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      const double xn = mesh.xNorms()(k) * ka;
      const double shape = std::max(0.0, ry - xn * xn);
      (*bound)(k) = shape;
      strip += shape;
    }
    sum += strip * mesh.nodeArea(j);
  }
  *bound *= (sum > 0.0) ? mu * fz / sum : 0.0;
}

void ForceSums::addStrip(const PatchMesh& mesh, int j, double tx, double ty, double xnTy, int stuck,
                         int loaded) {
  const double dA = mesh.nodeArea(j);
  f_.fx += tx * dA;
  f_.fy += ty * dA;
  f_.mz += (mesh.a() * xnTy - mesh.stripY(j) * tx) * dA;
  stuck_ += stuck * dA;
  loaded_ += loaded * dA;
}

CreepForces ForceSums::forces() const {
  CreepForces out = f_;
  out.adhesionFraction = loaded_ > 0.0 ? stuck_ / loaded_ : 0.0;
  return out;
}

CreepForces integrateTraction(const PatchMesh& mesh, const TractionField& f) {
  ForceSums sums;
  for (int j = 0; j < mesh.ny(); ++j) {
    double tx = 0.0, ty = 0.0, xnTy = 0.0;
    int stuck = 0, loaded = 0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      tx += f.tx(k);
      ty += f.ty(k);
      xnTy += mesh.xNorms()(k) * f.ty(k);
      loaded += f.bound(k) > 0.0;
      stuck += f.bound(k) > 0.0 && !f.slip(k);
    }
    sums.addStrip(mesh, j, tx, ty, xnTy, stuck, loaded);
  }
  return sums.forces();
}

CreepForces steadyFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                          TractionField* f) {
  const double gx = c.xi / L.L1, gy = c.eta / L.L2, gphi = c.phi / L.L3;
  ForceSums sums;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dx = mesh.stripStep(j), aj = mesh.stripHalfLength(j);
    const double sx = gx - gphi * mesh.stripY(j);
    double tx = 0.0, ty = 0.0, sumX = 0.0, sumY = 0.0, xnTy = 0.0;
    int stuck = 0, loaded = 0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      // Step from the upstream node (the leading edge for i = 0); the spin term is linear in x, so
      // its value at the step's midpoint integrates it exactly.
      const double h = (i == 0) ? 0.5 * dx : dx;
      const double xMid = aj - (i + 0.5) * dx + 0.5 * h;
      tx -= h * sx;
      ty -= h * (gy + gphi * xMid);
      const double t2 = tx * tx + ty * ty, g = f->bound(k);
      const bool slips = t2 > g * g;
      if (slips) {
        const double s = g / std::sqrt(t2);
        tx *= s;
        ty *= s;
      }
      f->tx(k) = tx;
      f->ty(k) = ty;
      f->slip(k) = slips;
      sumX += tx;
      sumY += ty;
      xnTy += mesh.xNorms()(k) * ty;
      loaded += g > 0.0;
      stuck += g > 0.0 && !slips;
    }
    sums.addStrip(mesh, j, sumX, sumY, xnTy, stuck, loaded);
  }
  return sums.forces();
}

}  // namespace wheel_rail_contact
