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

// The implicit update of one direction at one node: tau (1 + h beta) = tau_up + h beta tau_old
// - h (s_old / V + D), with beta = b0 / (V dt).
struct Direction {
  FilterZ z;
  double beta, invV, invDt;
  double guess(double up, double old, double s, double h, double drive) const {
    const double hb = h * beta;
    return (up + hb * old - h * (s * invV + drive)) / (1.0 + hb);
  }
  // Filter update from the final (saturated) traction.
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
  const Direction dx_{zx, std::max(0.0, zx.b0) / (V * dt), 1.0 / V, 1.0 / dt};
  const Direction dy_{zy, std::max(0.0, zy.b0) / (V * dt), 1.0 / V, 1.0 / dt};
  const double gx = c.xi / L.L1, gy = c.eta / L.L2, gphi = c.phi / L.L3;
  for (int j = 0; j < mesh.ny(); ++j) {
    const double dx = mesh.stripStep(j), aj = mesh.stripHalfLength(j);
    const double sx = gx - gphi * mesh.stripY(j);
    double tx = 0.0, ty = 0.0;
    for (int i = 0; i < mesh.nx(); ++i) {
      const int k = mesh.index(i, j);
      const double h = (i == 0) ? 0.5 * dx : dx;
      const double xMid = aj - (i + 0.5) * dx + 0.5 * h;
      const double ox = st->tx(k), oy = st->ty(k), qx = st->sx(k), qy = st->sy(k);
      tx = dx_.guess(tx, ox, qx, h, sx);
      ty = dy_.guess(ty, oy, qy, h, gy + gphi * xMid);
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
      st->sx(k) = dx_.nextState(tx, ox, qx);
      st->sy(k) = dy_.nextState(ty, oy, qy);
      st->tx(k) = tx;
      st->ty(k) = ty;
    }
  }
  return integrateTraction(mesh, *f);
}

namespace {

// Value of a strip's node field at continuous node index r (node i at r = i); zero at and beyond
// the strip's ends, which lie half an element outside the first and last node.
inline double alongStrip(const Eigen::ArrayXd& v, int base, int nx, double r) {
  if (r <= -0.5 || r >= nx - 0.5) return 0.0;
  if (r < 0.0) return v(base) * (1.0 + 2.0 * r);
  if (r >= nx - 1) return v(base + nx - 1) * (1.0 - 2.0 * (r - (nx - 1)));
  const int i0 = static_cast<int>(r);
  const double w = r - i0;
  return (1.0 - w) * v(base + i0) + w * v(base + i0 + 1);
}

}  // namespace

void remapState(const PatchMesh& from, const TransientState& in, const PatchMesh& to,
                TransientState* out) {
  const int nx = to.nx(), ny = to.ny();
  out->resize(to.size());
  const double sa = to.a() / from.a(), sb = to.b() / from.b();
  for (int j = 0; j < ny; ++j) {
    // Old strip coordinate of this new strip: old strip jj has its centre at s = jj.
    const double s = (sb * to.yNorm(j) + 1.0) * 0.5 * from.ny() - 0.5;
    const int last = from.ny() - 1;
    int strips[2];
    double weights[2];
    if (s < 0.0) {  // between the first strip's centre and the patch edge (zero traction)
      strips[0] = strips[1] = 0;
      weights[0] = std::max(0.0, 1.0 + 2.0 * s);
      weights[1] = 0.0;
    } else if (s > last) {
      strips[0] = strips[1] = last;
      weights[0] = std::max(0.0, 1.0 - 2.0 * (s - last));
      weights[1] = 0.0;
    } else {
      strips[0] = std::min(static_cast<int>(s), std::max(last - 1, 0));
      strips[1] = std::min(strips[0] + 1, last);
      weights[1] = s - strips[0];
      weights[0] = 1.0 - weights[1];
    }
    for (int q = 0; q < 2; ++q) {
      const int jj = strips[q];
      const double w = weights[q];
      if (w == 0.0) continue;
      const double half = from.halfNorm(jj);
      const int base = from.index(0, jj);
      for (int i = 0; i < nx; ++i) {
        const double X = sa * to.xNorm(i, j);
        const double r = ((1.0 - X / half) * from.nx() - 1.0) * 0.5;
        const int k = to.index(i, j);
        out->tx(k) += w * alongStrip(in.tx, base, from.nx(), r);
        out->ty(k) += w * alongStrip(in.ty, base, from.nx(), r);
        out->sx(k) += w * alongStrip(in.sx, base, from.nx(), r);
        out->sy(k) += w * alongStrip(in.sy, base, from.nx(), r);
      }
    }
  }
}

}  // namespace wheel_rail_contact
