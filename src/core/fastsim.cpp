#include "wheel_rail_contact/fastsim.hpp"

#include <algorithm>
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

namespace {

// Sum over one strip's nodes of max(0, ry - (c u)^2), u = nx - 1 - 2i (i = 0 .. nx-1), in closed
// form: the positive shapes are those with |u| < sqrt(ry) / c, and |u| runs over nx-1, nx-3, ...
// down to 1 (nx even, each value twice) or to 0 (nx odd, 0 once). A node exactly on the edge has
// shape 0, so whether it is counted does not matter.
double stripShapeSum(int nx, double ry, double c) {
  if (!(ry > 0.0)) return 0.0;
  const double U = std::min(std::sqrt(ry) / c, nx + 1.0);
  if (nx % 2 == 0) {  // u = 2t - 1, t = 1 .. nx/2
    const double m = std::min(nx / 2, static_cast<int>(0.5 * (U + 1.0)));
    return 2.0 * (m * ry - c * c * m * (4.0 * m * m - 1.0) / 3.0);
  }
  // u = 2t, t = 0 .. (nx-1)/2
  const double m = std::min((nx - 1) / 2, static_cast<int>(0.5 * U));
  return ry + 2.0 * (m * ry - c * c * 4.0 * m * (m + 1.0) * (2.0 * m + 1.0) / 6.0);
}

}  // namespace

void parabolicBound(const PatchMesh& mesh, double a, double b, double fz, double mu,
                    Eigen::ArrayXd* bound) {
  if (a == mesh.a() && b == mesh.b()) {  // the patch fills the mesh: precomputed shape
    *bound = mesh.pressureShape() * (mu * fz / (mesh.shapeIntegral() * a * b));
    return;
  }
  // The ellipse differs from the mesh's (fixed mesh sized for another load): node (x/a, y/b) on
  // the mesh is (ka x/a_mesh, kb y/b_mesh). The quadrature sum first (closed form per strip), then
  // one vectorisable pass, 1 - kb^2 (y/b_mesh)^2 - ka^2 (x/a_mesh)^2 from the mesh's own shape.
  const int nx = mesh.nx();
  const double ka = mesh.a() / a, kb = mesh.b() / b;
  double sum = 0.0;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double yn = mesh.yNorm(j) * kb;
    sum += stripShapeSum(nx, 1.0 - yn * yn, ka * mesh.halfNorm(j) / nx) * mesh.nodeArea(j);
  }
  const double scale = (sum > 0.0) ? mu * fz / sum : 0.0;
  *bound =
      (1.0 - kb * kb * (1.0 - mesh.pressureShape()) + (kb * kb - ka * ka) * mesh.xNorms().square())
          .max(0.0) *
      scale;
}

void ForceSums::addStrip(const PatchMesh& mesh, int j, StripSums s) {
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
  const FieldPointers out(f);
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
      strip.node(k, mesh.xNorms()(k), out.bound[k], &tx, &ty, out);
    }
    sums.addStrip(mesh, j, strip);
  }
  return sums.forces();
}

}  // namespace wheel_rail_contact
