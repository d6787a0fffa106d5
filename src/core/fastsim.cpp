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
  bound->resize(mesh.size());
  double sum = 0.0;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double y = mesh.stripY(j);
    const double ry = 1.0 - y * y / (b * b);
    double strip = 0.0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const double x = mesh.nodeX(i, j);
      const double shape = std::max(0.0, ry - x * x / (a * a));
      (*bound)(mesh.index(i, j)) = shape;
      strip += shape;
    }
    sum += strip * mesh.nodeArea(j);
  }
  *bound *= (sum > 0.0) ? mu * fz / sum : 0.0;
}

CreepForces integrateTraction(const PatchMesh& mesh, const TractionField& f) {
  CreepForces out;
  double loaded = 0.0, stuck = 0.0;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dA = mesh.nodeArea(j);
    const double y = mesh.stripY(j);
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      out.fx += f.tx(k) * dA;
      out.fy += f.ty(k) * dA;
      out.mz += (mesh.nodeX(i, j) * f.ty(k) - y * f.tx(k)) * dA;
      if (f.bound(k) > 0.0) {
        loaded += dA;
        if (!f.slip(k)) stuck += dA;
      }
    }
  }
  out.adhesionFraction = loaded > 0.0 ? stuck / loaded : 0.0;
  return out;
}

CreepForces steadyFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                          TractionField* f) {
  const double gx = c.xi / L.L1, gy = c.eta / L.L2, gphi = c.phi / L.L3;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dx = mesh.stripStep(j);
    const double aj = mesh.stripHalfLength(j);
    const double sx = gx - gphi * mesh.stripY(j);
    double tx = 0.0, ty = 0.0;
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
    }
  }
  return integrateTraction(mesh, *f);
}

}  // namespace wheel_rail_contact
