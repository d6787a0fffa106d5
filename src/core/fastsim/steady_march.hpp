/// The steady march's pieces shared by its scalar reference (fastsim.cpp) and its vector path
/// (strip_lanes.cpp): a strip's node, the step's constants, one strip at a time.
#pragma once

#include <algorithm>
#include <type_traits>

#include "core/fastsim/fastsim.hpp"
#include "core/fastsim/patch_mesh.hpp"

namespace wheel_rail_contact {
namespace steady {

// One strip of the steady march: its drive and running traction and sums. kCoupled: the x drive
// takes the lateral coupling (Flexibilities::lateralCoupling, perTy = its value times y_j) of the
// upstream node's lateral traction; the classic march is its own instance without it.
struct NoCoupling {
  NoCoupling() = default;
  NoCoupling(double) {}
};
template <bool kCoupled>
struct SteadyStrip {
  double dx, aj, sx, gy, gphi;
  [[no_unique_address]] std::conditional_t<kCoupled, double, NoCoupling> perTy;
  int k0;
  double tx = 0.0, ty = 0.0;
  StripSums sums = {};
  [[gnu::always_inline]] void node(int i, double h, const double* xn, const FieldPointers& out) {
    const int k = k0 + i;
    const UpstreamStep step(i, dx, aj, h);
    if constexpr (kCoupled)  // ty: still the upstream node's; the product off tx's chain
      tx = (tx - step.h * sx) - (step.h * perTy) * ty;
    else
      tx -= step.h * sx;
    ty -= step.h * (gy + gphi * step.xMid);
    sums.node(k, xn[k], out.bound[k], &tx, &ty, out);
  }
};

// A step's constants and the strips' marches from them.
template <bool kCoupled>
struct SteadyMarch {
  using Strip = SteadyStrip<kCoupled>;
  const PatchMesh& mesh;
  TractionField* f;
  FieldPointers out;
  const double* xn;
  int nx, ny;
  LateralDrive drive;
  double gx, gphiX, coupling;
  SteadyMarch(const PatchMesh& m, const Flexibilities& L, const Creepages& c, TractionField* field)
      : mesh(m),
        f(field),
        out(field),
        xn(m.xNorms().data()),
        nx(m.nx()),
        ny(m.ny()),
        drive(lateralDrive(L, c)),
        gx(c.xi / L.L1),
        gphiX(c.phi / L.spinX()),
        coupling(L.lateralCoupling) {}
  [[gnu::always_inline]] Strip strip(int j) const {
    return Strip{mesh.stripStep(j),
                 mesh.stripHalfLength(j),
                 gx - gphiX * mesh.stripY(j),
                 drive.gy,
                 drive.gphi,
                 coupling * mesh.stripY(j),
                 mesh.index(0, j)};
  }
  // Whether strip j has a loaded node.
  bool loaded(int j) const { return f->entry[j].first < nx - f->entry[j].first; }
  // Strip j's nodes outside the patch.
  void unloadedEnds(int j) const {
    const StripEntry& e = f->entry[j];
    const int k0 = mesh.index(0, j);
    for (int i = 0; i < std::min(e.first, nx); ++i) out.unloaded(k0 + i);
    for (int i = std::max(nx - e.first, e.first); i < nx; ++i) out.unloaded(k0 + i);
  }
  // Strip j's loaded nodes from node `from` on (the entry node, from the patch's leading edge,
  // where from is its first).
  [[gnu::always_inline]] void march(int j, Strip& s, int from) const {
    const StripEntry& e = f->entry[j];
    const int end = nx - e.first;
    if (from == e.first && from < end) s.node(from++, e.h, xn, out);
    for (int i = from; i < end; ++i) s.node(i, s.dx, xn, out);
  }
};

}  // namespace steady
}  // namespace wheel_rail_contact
