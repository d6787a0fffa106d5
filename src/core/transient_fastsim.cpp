#include "wheel_rail_contact/transient_fastsim.hpp"

#include <cmath>

namespace wheel_rail_contact {

void TransientState::resize(int n) {
  tx.setZero(n);
  ty.setZero(n);
  sx.setZero(n);
  sy.setZero(n);
}

void TransientState::clear() {
  tx.setZero();
  ty.setZero();
  sx.setZero();
  sy.setZero();
}

namespace {

// One direction's time term for this step. At a node the adhesion guess solves
// tau (1 + h beta) = tau_up + h beta tau_old - h (s_old / V + D), beta = b0 / (V dt); the filter
// state then advances from the final (saturated) traction.
struct Direction {
  FilterZ z;
  double beta, invV, invDt;
  double nextState(double tau, double old, double s) const {
    const double g = (tau - old) * invDt;
    return z.b1 * g - z.a1 * (z.b0 * g + s);
  }
};

}  // namespace

CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             TransientState* st, TractionField* f) {
  // A negative b0 (not produced by a fitted table) would make 1 + h beta vanish: clamp at zero,
  // i.e. drop the time term rather than divide by zero.
  const Direction X{zx, std::max(0.0, zx.b0) / (V * dt), 1.0 / V, 1.0 / dt};
  const Direction Y{zy, std::max(0.0, zy.b0) / (V * dt), 1.0 / V, 1.0 / dt};
  const double gx = c.xi / L.L1, gy = c.eta / L.L2, gphi = c.phi / L.L3;
  ForceSums sums;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dx = mesh.stripStep(j), aj = mesh.stripHalfLength(j);
    const double sx = gx - gphi * mesh.stripY(j);
    double tx = 0.0, ty = 0.0;
    StripSums strip;
    // 1 / (1 + h beta) for the half step at the leading edge and the full steps after it.
    const double ix[2] = {1.0 / (1.0 + 0.5 * dx * X.beta), 1.0 / (1.0 + dx * X.beta)};
    const double iy[2] = {1.0 / (1.0 + 0.5 * dx * Y.beta), 1.0 / (1.0 + dx * Y.beta)};
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      const int full = i > 0;
      const UpstreamStep step(i, dx, aj);
      const double h = step.h, xMid = step.xMid;
      const double ox = st->tx(k), oy = st->ty(k), qx = st->sx(k), qy = st->sy(k);
      tx = (tx + h * (X.beta * ox - qx * X.invV - sx)) * ix[full];
      ty = (ty + h * (Y.beta * oy - qy * Y.invV - gy - gphi * xMid)) * iy[full];
      strip.node(k, mesh.xNorms()(k), f->bound(k), &tx, &ty, f);
      st->sx(k) = X.nextState(tx, ox, qx);
      st->sy(k) = Y.nextState(ty, oy, qy);
      st->tx(k) = tx;
      st->ty(k) = ty;
    }
    sums.addStrip(mesh, j, strip);
  }
  return sums.forces();
}

CreepForces holdTraction(const PatchMesh& mesh, TransientState* st, TractionField* f) {
  for (int k = 0; k < mesh.size(); ++k) {
    const double t = std::hypot(st->tx(k), st->ty(k)), g = f->bound(k);
    if (t > g) {
      const double s = g / t;
      st->tx(k) *= s;
      st->ty(k) *= s;
      f->slip(k) = true;
    }
    f->tx(k) = st->tx(k);
    f->ty(k) = st->ty(k);
  }
  return integrateTraction(mesh, *f);
}

namespace {

// Linear interpolation along one old strip at continuous node index r (node i at r = i): the two
// nodes and their weights. The strip's ends lie half an element outside its first and last node
// and carry zero traction; beyond them both weights are zero.
struct AlongStrip {
  int i0 = 0;
  double w0 = 0.0, w1 = 0.0;
  AlongStrip(double r, int nx) {
    if (r <= -0.5 || r >= nx - 0.5) return;
    if (r < 0.0) {
      w0 = 1.0 + 2.0 * r;
    } else if (r >= nx - 1) {
      i0 = nx - 1;
      w0 = 1.0 - 2.0 * (r - (nx - 1));
    } else {
      i0 = static_cast<int>(r);
      w1 = r - i0;
      w0 = 1.0 - w1;
      if (i0 + 1 >= nx) w1 = 0.0;
    }
  }
};

// The (at most two) old strips around normalised old coordinate s (strip jj centred at s = jj),
// with weights; towards the patch's lateral edge the weight falls to zero half a strip out.
int stripsAround(double s, int ny, int strips[2], double weights[2]) {
  const int last = ny - 1;
  if (s < 0.0 || s > last) {
    strips[0] = s < 0.0 ? 0 : last;
    weights[0] = std::max(0.0, 1.0 - 2.0 * (s < 0.0 ? -s : s - last));
    return weights[0] > 0.0 ? 1 : 0;
  }
  strips[0] = std::min(static_cast<int>(s), std::max(last - 1, 0));
  strips[1] = std::min(strips[0] + 1, last);
  weights[1] = s - strips[0];
  weights[0] = 1.0 - weights[1];
  return 2;
}

}  // namespace

void remapState(const PatchMesh& from, const TransientState& in, const PatchMesh& to,
                TransientState* out) {
  const int nx = to.nx(), ny = to.ny(), oldNx = from.nx();
  out->resize(to.size());
  const double sa = to.a() / from.a(), sb = to.b() / from.b();
  for (int j = 0; j < ny; ++j) {
    int strips[2];
    double weights[2];
    const int n =
        stripsAround((sb * to.yNorm(j) + 1.0) * 0.5 * from.ny() - 0.5, from.ny(), strips, weights);
    for (int q = 0; q < n; ++q) {
      const int jj = strips[q], base = from.index(0, jj);
      const double w = weights[q];
      // Old node index is linear in the new one: r(i) = r0 + i dr.
      const double ratio = sa * to.halfNorm(j) / from.halfNorm(jj);
      const double r0 = ((1.0 - ratio * (1.0 - 1.0 / nx)) * oldNx - 1.0) * 0.5;
      const double dr = ratio * oldNx / nx;
      for (int i = 0; i < nx; ++i) {
        const AlongStrip at(r0 + i * dr, oldNx);
        const int k = to.index(i, j), k0 = base + at.i0, k1 = base + std::min(at.i0 + 1, oldNx - 1);
        const double w0 = w * at.w0, w1 = w * at.w1;
        out->tx(k) += w0 * in.tx(k0) + w1 * in.tx(k1);
        out->ty(k) += w0 * in.ty(k0) + w1 * in.ty(k1);
        out->sx(k) += w0 * in.sx(k0) + w1 * in.sx(k1);
        out->sy(k) += w0 * in.sy(k0) + w1 * in.sy(k1);
      }
    }
  }
}

}  // namespace wheel_rail_contact
