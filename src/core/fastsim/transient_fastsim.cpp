#include "core/fastsim/transient_fastsim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/fastsim/strip_lanes.hpp"
#include "core/fastsim/transient_march.hpp"

namespace wheel_rail_contact {

namespace {

// The nodes i of a strip of nx outside the patch for exactly one of the entries e0, e1
// (StripEntry::first): node i is outside for e when i < e or i >= nx - e, taken as one range at
// each end split at the strip's middle m, so that no node is in both. With e0 = 0: those outside
// for e1.
template <class Visit>
void acrossEdge(int nx, int e0, int e1, Visit&& visit) {
  const int m = (nx + 1) / 2, lo = std::min(e0, e1), hi = std::max(e0, e1);
  for (int i = std::min(lo, m); i < std::min(hi, m); ++i) visit(i);
  for (int i = std::max(nx - hi, m); i < std::max(nx - lo, m); ++i) visit(i);
}

}  // namespace

void TransientState::resize(int n) {
  history_.setZero(kRows, n);
  ends_.reserve(n);  // a strip count is at most n: the march's books never allocate
  stripSums_.reserve(n);
  from_.reserve(n);
  decaying_ = false;
  decay_.setOnes();
}

void TransientState::clear() {
  history_.setZero();
  decaying_ = false;
  decay_.setOnes();
}

void TransientState::restoreDecayed() const {
  for (std::size_t j = 0; j < ends_.size(); ++j)
    acrossEdge(nx_, 0, ends_[j], [&](int i) { history_.col(j * nx_ + i).segment<2>(2) *= decay_; });
  decaying_ = false;
  decay_.setOnes();
}

void TransientState::scaleStates(double r, bool second) {
  history_.middleRows<2>(2) *= r;
  if (second) history_.bottomRows<2>() *= r;
}

void TransientState::scaleDirections(double rx, double ry) {
  // Rows x, y alternate (tx, ty, sx, sy, s2x, s2y); sx, sy held decayed scale alike.
  for (int row = 0; row < kRows; ++row) history_.row(row) *= row % 2 == 0 ? rx : ry;
}

// The march's pieces (transient_march.hpp).
using namespace transient;

namespace {

// The scalar reference: one strip at a time, in strip order.
template <bool kSecond, bool kResidualAlongTraction, class Source>
CreepForces marchStrips(const TransientStep& step, const Source& source) {
  const transient::TransientMarch<kSecond, kResidualAlongTraction, Source> m(step, source);
  m.outside();
  // Plain locals: held in registers, not reloaded after the march's stores.
  const auto update = m.update;
  const Source history = m.history;
  const FieldPointers out = m.out;
  const double* const xn = m.xn;
  ForceSums sums;
  for (int j = 0; j < m.ny; ++j) {
    auto A = m.strip(j);
    // The first loaded node steps from the patch's leading edge, where the traction is zero.
    if (A.enter < A.leave) A.node(A.enter, A.entry, history, xn, out, update);
    for (int k = A.enter + 1; k < A.leave; ++k) A.node(k, A.full, history, xn, out, update);
    sums.addStrip(m.mesh, j, A.sums, step.f->entry[j], out.tx, out.ty);
  }
  return sums.forces();
}

// The march `step` asks for: in lanes (strip_lanes.hpp) where TransientState says so, else the
// scalar reference, with the saturation TransientState::Saturation names, chosen once a step.
template <class Source>
CreepForces march(const TransientStep& step, const Source& source) {
  if (step.st->marchesInLanes(step.mesh.nx())) return transientFastSimInLanes(step);
  const bool residual = step.st->saturation() == TransientState::Saturation::kResidualAlongTraction;
  if (step.second)
    return residual ? marchStrips<true, true>(step, source)
                    : marchStrips<true, false>(step, source);
  return residual ? marchStrips<false, true>(step, source)
                  : marchStrips<false, false>(step, source);
}

}  // namespace

// Before the in-place first-order march: whether the nodes outside the patch go lazily this step
// (d: the decay of their states per step, -poleOld). A node entering the patch is restored (s =
// held D); one staying outside only gets its field written; one leaving it is left to the march's
// outside pass (from_), which takes the full update. A d not safely inside (1e-3, 1e3) in size
// (shen-li's F = 1 has d = 0), or a D leaving (1e-100, 1e100), materializes: the march then takes
// every outside node in full.
bool TransientStorage::lazyBefore(const PatchMesh& mesh, const std::vector<StripEntry>& entries,
                                  const Eigen::Array2d& d, TransientState* st, TractionField* f) {
  const int nx = mesh.nx(), ny = mesh.ny();
  // Nothing held and nothing outside (a mesh fitted to the patch): no books to keep.
  bool outside = st->decaying_;
  for (int j = 0; j < ny && !outside; ++j) outside = entries[j].first > 0;
  if (!outside) {
    fromZero(ny, st);
    return false;
  }
  const bool lazy = (d.abs() > 1e-3).all() && (d.abs() < 1e3).all();
  const Pair next = st->decay_ * d;
  if (!lazy || !((next.abs() > 1e-100).all() && (next.abs() < 1e100).all()) || st->nx_ != nx ||
      static_cast<int>(st->ends_.size()) != ny) {
    eager(ny, st);
    if (!lazy) return false;
  }
  if (!st->decaying_) st->ends_.assign(ny, 0);
  if (static_cast<int>(st->from_.size()) != ny) st->from_.assign(ny, 0);
  st->fromZero_ = false;
  const Pair held = st->decay_;
  double* const history = stored(st);
  const FieldPointers out(f);
  for (int j = 0; j < ny; ++j) {
    const int first = mesh.index(0, j), e0 = st->ends_[j], e1 = std::min(entries[j].first, nx);
    if (e1 < e0)
      acrossEdge(nx, e0, e1, [&](int i) {
        double* const p = history + kPerNode * (first + i) + kState;
        storePair(p, pairAt(p) * held);
      });
    acrossEdge(nx, 0, std::min(e0, e1), [&](int i) { out.unloaded(first + i); });
    st->from_[j] = std::min(e0, e1);
  }
  return true;
}

// After it: the nodes that left the patch, updated by the march, are held over the new D.
void TransientStorage::lazyAfter(const PatchMesh& mesh, const std::vector<StripEntry>& entries,
                                 const Eigen::Array2d& d, TransientState* st) {
  const int nx = mesh.nx(), ny = mesh.ny();
  const Pair D = st->decay_ * d;  // decay_ is 1 when nothing was held
  double* const history = stored(st);
  for (int j = 0; j < ny; ++j) {
    const int first = mesh.index(0, j), e0 = st->ends_[j], e1 = std::min(entries[j].first, nx);
    if (e1 > e0)
      acrossEdge(nx, e0, e1, [&](int i) {
        double* const p = history + kPerNode * (first + i) + kState;
        storePair(p, pairAt(p) / D);
      });
    st->ends_[j] = e1;
  }
  st->nx_ = nx;
  st->decay_ = D;
  st->decaying_ = true;
}

bool TransientState::marchesInLanes(int nx) const {
  switch (stripLanes_) {
    case StripLanes::kOff:
      return false;
    case StripLanes::kOn:
      return stripLanesAvailable();
    case StripLanes::kAuto:
      break;
  }
  return nx >= kLanesFromNodes && stripLanesAvailable();
}

CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, TransientState* st, TractionField* f,
                             bool marchSecond) {
  const bool second = marchSecond || zx.secondOrder() || zy.secondOrder();
  const TransientStep step{mesh,         L,       c,       V,  dt, zx,    zy,
                           historyScale, nullptr, nullptr, st, f,  second};
  if (second) {
    TransientStorage::eager(mesh.ny(), st);  // the second-order march reads every node as it is
    return march(step, InPlace{});
  }
  // Outside the patch the traction is zero and s <- -poleOld s, i.e. d = -a1 r (TimeTerm).
  const Pair d(-zx.a1 * historyScale, -zy.a1 * historyScale);
  const bool lazy = TransientStorage::lazyBefore(mesh, f->entry, d, st, f);
  const CreepForces forces = march(step, InPlace{});
  if (lazy) TransientStorage::lazyAfter(mesh, f->entry, d, st);
  return forces;
}

CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, const AlongStripMap& map,
                             const TransientState& previous, TransientState* st, TractionField* f,
                             bool marchSecond) {
  TransientStorage::writtenInFull(mesh.ny(), st);
  const bool second = marchSecond || zx.secondOrder() || zy.secondOrder();
  const TransientStep step{mesh, L, c, V, dt, zx, zy, historyScale, &map, &previous, st, f, second};
  return march(step, CarriedHistory(map, previous));  // reads `previous` materialized
}

AlongStripMap::AlongStripMap(int nx) : offset_(nx, 0), weights_(4, nx) {}

void AlongStripMap::set(double ratio) {
  // New node i sits at t_i = 1 - (2i + 1)/nx of its strip (t = x / a_j); at fixed x its old t is
  // ratio t_i, i.e. old node index r = r0 + i dr.
  const int nx = nodes();
  const double r0 = ((1.0 - ratio * (1.0 - 1.0 / nx)) * nx - 1.0) * 0.5, dr = ratio;
  // Raw pointers: through the members, every store of an offset reloaded the weights' address.
  std::ptrdiff_t* const offset = offset_.data();
  double* const spread = weights_.data();
  for (int i = 0; i < nx; ++i) {
    const double r = r0 + i * dr;
    // f is r's offset from node index[i]. Between the first and the last node the weights are
    // (1 - f, f), f in [0, 1]; the strip's ends lie half an element beyond its first and last node
    // and carry zero traction, so towards them the weight falls to zero over that half element
    // (c0 = 1 + 2f for f < 0, c1 = 3 - 2f for f > 1); beyond the ends both are zero.
    const bool inside = r >= 0.0 && r <= nx - 1.0;
    const double rc = inside ? r : std::min(std::max(r, -1.0), double(nx));
    const std::ptrdiff_t index =
        std::min(static_cast<std::ptrdiff_t>(std::max(rc, 0.0)), std::ptrdiff_t{nx - 2});
    offset[i] = index * TransientState::kRows;
    const double f = rc - index;
    const Eigen::Array2d w =
        inside
            ? Eigen::Array2d(1.0 - f, f)
            : Eigen::Array2d(1.0 - f, f).min(Eigen::Array2d(1.0 + 2.0 * f, 3.0 - 2.0 * f)).max(0.0);
    Eigen::Map<Eigen::Array4d, Eigen::Aligned16> to(spread + 4 * i);
    to << w(0), w(0), w(1), w(1);
  }
}

void remapAlongStrips(const AlongStripMap& map, const TransientState& in, int strips,
                      TransientState* out) {
  const CarriedHistory source(map, in);
  for (int j = 0; j < strips; ++j) {
    const double* const strip = source.strip(j, map.nodes());
    for (int i = 0; i < map.nodes(); ++i) {
      const History h = source.at<true>(strip, i);
      const int k = j * map.nodes() + i;
      TransientStorage::column(out, k) << h.t, h.s, h.s2;
    }
  }
  TransientStorage::writtenInFull(strips, out);
}

CreepForces holdTraction(const PatchMesh& mesh, TransientState* st, TractionField* f) {
  for (int k = 0; k < mesh.size(); ++k) {
    auto traction = TransientStorage::column(st, k).head<2>();  // never held decayed
    const double t = std::hypot(traction(0), traction(1)), g = f->bound(k);
    if (t > g) {
      traction *= g / t;
      f->slip(k) = true;
    }
    f->tx(k) = traction(0);
    f->ty(k) = traction(1);
  }
  return integrateTraction(mesh, *f);
}

namespace {

// Linear interpolation along one old strip at continuous node index r (node i at r = i): the two
// nodes and their weights. The strip's ends lie half an element outside its first and last node
// and carry zero traction; beyond them both weights are zero.
struct StripInterpolation {
  int i0 = 0;
  double w0 = 0.0, w1 = 0.0;
  StripInterpolation(double r, int nx) {
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
        const StripInterpolation at(r0 + i * dr, oldNx);
        const int k = to.index(i, j), k0 = base + at.i0, k1 = base + std::min(at.i0 + 1, oldNx - 1);
        const double w0 = w * at.w0, w1 = w * at.w1;
        TransientStorage::column(out, k) += w0 * TransientStorage::materializedColumn(in, k0) +
                                            w1 * TransientStorage::materializedColumn(in, k1);
      }
    }
  }
}

double remapAtFixedPoints(const PatchMesh& from, double fromOrigin, const TransientState& in,
                          const PatchMesh& to, double toOrigin, TransientState* out) {
  const int nx = to.nx(), oldNx = from.nx(), oldNy = from.ny();
  out->resize(to.size());
  // Old strip q spans [lo_q, hi_q] about its centre Y_q: touching neighbours interpolate between
  // centres, a free edge takes the strip's value falling to zero at the edge.
  auto centre = [&](int q) { return fromOrigin + from.stripY(q); };
  auto halfWidth = [&](int q) { return 0.5 * from.stripWidth(q); };
  auto touches = [&](int q) {  // strip q and q + 1 share an edge
    const double gap = (centre(q + 1) - halfWidth(q + 1)) - (centre(q) + halfWidth(q));
    return gap <= 1e-6 * (halfWidth(q) + halfWidth(q + 1));
  };
  int reached = 0;
  for (int j = 0; j < to.ny(); ++j) {
    const double Y = toOrigin + to.stripY(j);
    int strips[2] = {0, 0};
    double weights[2] = {0.0, 0.0};
    int n = 0;
    // The last old strip whose centre lies at or below Y (-1: none).
    int q = -1;
    for (int k = 0; k < oldNy && centre(k) <= Y; ++k) q = k;
    auto edgeWeight = [&](int k) {
      return std::max(0.0, 1.0 - std::abs(Y - centre(k)) / halfWidth(k));
    };
    if (q >= 0 && q + 1 < oldNy && touches(q)) {
      const double t = (Y - centre(q)) / (centre(q + 1) - centre(q));
      strips[0] = q;
      weights[0] = 1.0 - t;
      strips[1] = q + 1;
      weights[1] = t;
      n = 2;
    } else {
      if (q >= 0 && edgeWeight(q) > 0.0) {
        strips[n] = q;
        weights[n++] = edgeWeight(q);
      }
      if (q + 1 < oldNy && edgeWeight(q + 1) > 0.0) {
        strips[n] = q + 1;
        weights[n++] = edgeWeight(q + 1);
      }
    }
    bool any = false;
    for (int m = 0; m < n; ++m) {
      const int jj = strips[m], base = from.index(0, jj);
      const double w = weights[m], A = from.stripHalfLength(jj), dx = from.stripStep(jj);
      for (int i = 0; i < nx; ++i) {
        const StripInterpolation at((A - to.nodeX(i, j)) / dx - 0.5, oldNx);
        const double w0 = w * at.w0, w1 = w * at.w1;
        if (w0 == 0.0 && w1 == 0.0) continue;
        const int k = to.index(i, j), k0 = base + at.i0, k1 = base + std::min(at.i0 + 1, oldNx - 1);
        TransientStorage::column(out, k) += w0 * TransientStorage::materializedColumn(in, k0) +
                                            w1 * TransientStorage::materializedColumn(in, k1);
        any = true;
      }
    }
    if (any) ++reached;  // counted by strip: a strip reached carries history along its length
  }
  return to.ny() > 0 ? double(reached) / to.ny() : 0.0;
}

}  // namespace wheel_rail_contact
