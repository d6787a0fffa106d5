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

StepOutput stepOutput(const CreepForces& f, double fz, double a, double b) {
  StepOutput out;
  out.fx = f.fx;
  out.fy = f.fy;
  out.mz = f.mz;
  out.fz = fz;
  out.a = a;
  out.b = b;
  out.adhesionFraction = f.adhesionFraction;
  return out;
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

void StripSums::node(int k, double xn, double g, double* tx, double* ty, TractionField* f) {
  const double t2 = *tx * *tx + *ty * *ty;
  // Below about 1e-150 Pa the squares underflow to 0 and a traction above a zero bound stayed
  // (found by fuzzing): measure |t| by hypot there.
  const double t = t2 > 1e-300 ? std::sqrt(t2) : std::hypot(*tx, *ty);
  const bool slips = t > g;
  if (slips) {
    const double s = g / t;
    *tx *= s;
    *ty *= s;
  }
  f->tx(k) = *tx;
  f->ty(k) = *ty;
  f->slip(k) = slips;
  this->tx += *tx;
  this->ty += *ty;
  xnTy += xn * *ty;
  loaded += g > 0.0;
  stuck += g > 0.0 && !slips;
}

void ForceSums::addStrip(const PatchMesh& mesh, int j, const StripSums& s) {
  const double dA = mesh.nodeArea(j);
  f_.fx += s.tx * dA;
  f_.fy += s.ty * dA;
  f_.mz += (mesh.a() * s.xnTy - mesh.stripY(j) * s.tx) * dA;
  stuck_ += s.stuck * dA;
  loaded_ += s.loaded * dA;
}

CreepForces ForceSums::forces() const {
  CreepForces out = f_;
  out.adhesionFraction = loaded_ > 0.0 ? stuck_ / loaded_ : 0.0;
  return out;
}

CreepForces integrateTraction(const PatchMesh& mesh, const TractionField& f) {
  ForceSums sums;
  for (int j = 0; j < mesh.ny(); ++j) {
    StripSums strip;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      strip.tx += f.tx(k);
      strip.ty += f.ty(k);
      strip.xnTy += mesh.xNorms()(k) * f.ty(k);
      strip.loaded += f.bound(k) > 0.0;
      strip.stuck += f.bound(k) > 0.0 && !f.slip(k);
    }
    sums.addStrip(mesh, j, strip);
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
    double tx = 0.0, ty = 0.0;
    StripSums strip;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      const UpstreamStep step(i, dx, aj);
      tx -= step.h * sx;
      ty -= step.h * (gy + gphi * step.xMid);
      strip.node(k, mesh.xNorms()(k), f->bound(k), &tx, &ty, f);
    }
    sums.addStrip(mesh, j, strip);
  }
  return sums.forces();
}

}  // namespace wheel_rail_contact
