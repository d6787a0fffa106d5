/// The time-term march's pieces shared by its scalar reference (transient_fastsim.cpp) and its
/// vector path (strip_lanes.cpp): the storage's access, the step's constants, a strip's node, the
/// nodes outside the patch, one strip at a time.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/fastsim/transient_fastsim.hpp"

namespace wheel_rail_contact {
// The marches' access to TransientState's storage.
struct TransientStorage {
  // As stored: outside the patch sx, sy may be held decayed (only the in-place first-order march
  // keeps those books; it reads no such node).
  static double* stored(TransientState* s) { return s->history_.data(); }
  static const double* stored(const TransientState& s) { return s.history_.data(); }
  // The state itself, for a march that reads every node.
  static const double* materialized(const TransientState& s) { return s.materializedRows().data(); }
  static auto column(TransientState* s, int k) { return s->history_.col(k); }
  static auto materializedColumn(const TransientState& s, int k) {
    return s.materializedRows().col(k);
  }
  // Room for every strip's sums (ny at most the node count: no allocation).
  static StripSums* stripSums(int strips, TransientState* s) {
    s->stripSums_.resize(strips);
    return s->stripSums_.data();
  }
  // Per strip, where the outside pass of the march starts (0: every outside node).
  static const int* outsideFrom(const TransientState& s) { return s.from_.data(); }
  // The march's outside pass takes every outside node.
  static void fromZero(int strips, TransientState* s) {
    if (s->fromZero_ && static_cast<int>(s->from_.size()) == strips) return;
    s->from_.assign(strips, 0);
    s->fromZero_ = true;
  }
  // Every outside node taken in full by the march, nothing held.
  static void eager(int strips, TransientState* s) {
    s->materialize();
    fromZero(strips, s);
  }
  // A march that writes every node of s holds nothing decayed.
  static void writtenInFull(int strips, TransientState* s) {
    s->decaying_ = false;
    s->decay_.setOnes();
    fromZero(strips, s);
  }
  static bool lazyBefore(const PatchMesh& mesh, const std::vector<StripEntry>& entries,
                         const Eigen::Array2d& d, TransientState* st, TractionField* f);
  static void lazyAfter(const PatchMesh& mesh, const std::vector<StripEntry>& entries,
                        const Eigen::Array2d& d, TransientState* st);
};

namespace transient {
// One direction's time term for this step (doc/method.md#dynamic-flexibility, Tustin filter in
// transposed direct form II). The stored history (tau_old, s_old) is read times r, the history
// scale (the caller's rescaling to the current patch, see NssModel), so no pass over it is needed.
// At a node the adhesion guess solves
//   tau (1 + h beta) = tau_up + h (beta r tau_old - r s_old / V - drive),  beta = b0 / (V dt),
// and the filter state advances from the final (saturated) traction, g = (tau - r tau_old) / dt:
//   s = b1 g - a1 (b0 g + r s_old) = rate tau - rate r tau_old - a1 r s_old.
// A second-order filter adds r s2_old to s and keeps (h = b0 g + r s_old as before)
//   s2 = b2 g - a2 (b0 g + r s_old) = rate2 tau - rate2 r tau_old - a2 r s_old.
// The guess sees only h, i.e. b0 and s_old: s2 reaches the traction one step later, through s.
struct TimeTerm {
  double beta, lagPerLength, rate, rateOld, poleOld;
  TimeTerm(const FilterZ& z, double V, double dt, double r)
      // A negative b0 (not produced by a fitted table) would make 1 + h beta vanish: clamp at
      // zero, i.e. drop the time term rather than divide by zero.
      : beta(std::max(0.0, z.b0) / (V * dt)),
        lagPerLength(r / V),
        rate((z.b1 - z.a1 * z.b0) / dt),
        rateOld(rate * r),
        poleOld(z.a1 * r) {}
  double nextState(double tau, double old, double s) const {
    return rate * tau - rateOld * old - poleOld * s;
  }
};

// The (x, y) pair of one per-node quantity: what does not depend on the upstream traction (the
// history's part of the guess, the filter state's update) is computed for both directions at once.
using Pair = Eigen::Array2d;

// Strip j's x drive (gx less spin's part at the strip's y) and its lateral coupling times y:
// PackedStep's arguments that differ by strip, taken alike by the scalar reference and the lanes.
struct StripDrives {
  double x, perTy;
  StripDrives(const PatchMesh& mesh, int j, double gx, double gphiX, double coupling)
      : x(gx - gphiX * mesh.stripY(j)), perTy(coupling * mesh.stripY(j)) {}
};

// Both directions' adhesion guesses for a step of length h along a strip, every factor that does
// not change along the strip folded in, as (x, y) pairs:  tau = history + decay tau_up, with
// history = memory tau_old - lag s_old - push (push: the rigid slip over L, times h). Spin drives y
// linearly in x; over a step it is taken at the step's midpoint x + h/2 (exact for a linear term):
// push_y = p0 + pushPerXn x/a. The upstream decay stays scalar, on the march's serial chain.
// The lateral coupling (Flexibilities::lateralCoupling, perTy its value times the strip's y) adds
// h perTy tau_y,up to the x drive, tau_y,up taken as the upstream node's lateral traction of the
// step before (r times): coupleX tau_y,old,up off the x guess, off the march's serial chain, and
// equal to steady FastSim's coupling at a fixed point (the calibrated march only; 0 without a
// coupling).
struct PackedStep {
  Pair memory, lag, push;
  Pair scaledInverseDecay;  // r (1 + h beta) (slipsAlongTheResidual)
  Pair decaySwapped;        // (decayY, decayX) (slipsAlongTheResidual)
  double squaredScale;      // r^2 (slipsAlongTheResidual)
  double decayX, decayY, pushPerXn;
  double coupleX;  // r h perTy decayX
  // beta: (X.beta, Y.beta); lagPerLength is the same for both directions.
  PackedStep(const Pair& beta, double lagPerLength, double r, double h, double driveX, double gy,
             double gphi, double a, double perTy) {
    const Pair hb = h * beta, decay = 1.0 / (1.0 + hb);
    decaySwapped = Pair(decay(1), decay(0));
    memory = hb * r * decay;
    scaledInverseDecay = r * (1.0 + hb);
    squaredScale = r * r;
    lag = h * lagPerLength * decay;
    push = h * Pair(driveX, gy + 0.5 * h * gphi) * decay;
    decayX = decay(0);
    decayY = decay(1);
    pushPerXn = h * gphi * a * decayY;
    coupleX = r * h * perTy * decay(0);
  }
};

// The (x, y) pair at p, one aligned load or store: TransientState's columns (6 doubles) start on
// 16 bytes, and so do their pairs (and the carry's spread weights).
inline Pair pairAt(const double* p) {
  return Eigen::Map<const Pair, Eigen::Aligned16>(p);
}
inline void storePair(double* p, const Pair& v) {
  Eigen::Map<Pair, Eigen::Aligned16> to(p);
  to = v;
}

// A node's history as the march reads it: the traction and the filter states, (x, y) pairs (s2
// read only by the second-order march).
struct History {
  Pair t, s, s2;
};

// Where TransientState keeps node k: its traction at history + 6k, its filter state 2 further, its
// second filter state 4 further.
constexpr int kTraction = 0, kState = 2, kSecondState = 4, kPerNode = TransientState::kRows;

// The history in place: node k of the state the march also writes.
struct InPlace {
  static constexpr bool kMapped = false;
  const double* history = nullptr;
  // Read where the march writes: taken from the same state as the writes' pointer, so that the
  // compiler sees one pointer (one induction variable, not two).
  void writesTo(const TransientState& s) { history = TransientStorage::stored(s); }
  // Strip j's node 0 (of `nodes` per strip): node i of the strip is `strip` + kPerNode i.
  const double* strip(int j, int nodes) const { return history + kPerNode * nodes * j; }
  template <bool kSecond>
  History at(const double* strip, int i) const {
    const double* p = strip + kPerNode * i;
    return {pairAt(p + kTraction), pairAt(p + kState), kSecond ? pairAt(p + kSecondState) : Pair()};
  }
};

// The history of the previous patch, carried along the strips (AlongStripMap) node by node as the
// march reads it: no pass of its own, and the old state is read where the march needs it. Raw
// pointers, held in registers: through references they were reloaded after every store of the
// march's slip flags (a bool store may alias anything).
struct CarriedHistory {
  static constexpr bool kMapped = true;  // every strip reads through the same map
  const std::ptrdiff_t* offsets;         // AlongStripMap::historyOffsets
  const double* weights;
  std::ptrdiff_t nodes;
  const double* history;
  CarriedHistory(const AlongStripMap& map, const TransientState& s)
      : offsets(map.historyOffsets()),
        weights(map.spreadWeights()),
        nodes(map.nodes()),
        history(TransientStorage::materialized(s)) {}
  void writesTo(const TransientState&) {}  // reads `previous`, never the state written
  // The old strip j's first node (old and new patch share the layout): per node the march then
  // only adds the map's offset.
  const double* strip(int j, int) const { return history + kPerNode * nodes * j; }
  // As AlongStripMap::read, w0 v0 + w1 v1, for both directions at once: the pair at `offset` of
  // old nodes index(i) and index(i) + 1 of the strip.
  [[gnu::always_inline]] Pair carried(const double* strip, int offset, int i) const {
    const double* p = strip + offsets[i] + offset;
    return pairAt(weights + 4 * i) * pairAt(p) + pairAt(weights + 4 * i + 2) * pairAt(p + kPerNode);
  }
  template <bool kSecond>
  [[gnu::always_inline]] History at(const double* strip, int i) const {
    return {carried(strip, kTraction, i), carried(strip, kState, i),
            kSecond ? carried(strip, kSecondState, i) : Pair()};
  }
};

// A second-order F's own constants: empty for first order, so the first-order march neither sets
// them up nor copies them.
template <bool kSecond>
struct SecondStateUpdate {
  SecondStateUpdate(const FilterZ&, const FilterZ&, double, double) {}
};
template <>
struct SecondStateUpdate<true> {
  Pair rate2, rate2Old, pole2Old;
  double r;
  SecondStateUpdate(const FilterZ& zx, const FilterZ& zy, double dt, double ratio)
      : rate2(Pair(zx.b2 - zx.a2 * zx.b0, zy.b2 - zy.a2 * zy.b0) / dt),
        rate2Old(rate2 * ratio),
        pole2Old(Pair(zx.a2, zy.a2) * ratio),
        r(ratio) {}
};

// The filter states' update at a node from its final traction t and history (old, s, s2):
// TimeTerm's algebra for both directions. First order: s only; second order: s and s2. Writes the
// node's new history: t and the states.
template <bool kSecond>
struct StateUpdate {
  Pair rate, rateOld, poleOld;
  double* written;  // the new history (TransientState::history)
  SecondStateUpdate<kSecond> second;
  StateUpdate(const TimeTerm& X, const TimeTerm& Y, const FilterZ& zx, const FilterZ& zy, double dt,
              double r, TransientState* st)
      : rate(X.rate, Y.rate),
        rateOld(X.rateOld, Y.rateOld),
        poleOld(X.poleOld, Y.poleOld),
        written(TransientStorage::stored(st)),
        second(zx, zy, dt, r) {}
  // o: the node's history, read before these stores (in place, they overwrite it).
  [[gnu::always_inline]] void operator()(int k, const Pair& t, const History& o) const {
    const Pair &old = o.t, &s = o.s;
    Pair next = rate * t - rateOld * old - poleOld * s;  // TimeTerm::nextState
    if constexpr (kSecond) {
      next += second.r * o.s2;
      storePair(written + kPerNode * k + kSecondState,
                second.rate2 * t - second.rate2Old * old - second.pole2Old * s);
    }
    double* const p = written + kPerNode * k;
    storePair(p + kState, next);
    storePair(p + kTraction, t);
  }
};

// A slipping node under TransientState::Saturation::kResidualAlongTraction; false (nothing done)
// if the guess (tx, ty) does not slip. Per direction i the adhesion guess solves
//   (1 + h beta_i) tau_i = rhs_i = v_i + h beta_i r tau_old_i,
// v_i the steady slip equation's part (upstream traction, drive, filter state). Scaling the guess
// onto the bound g keeps the direction of rhs_i / (1 + h beta_i): with x and y on different filters
// (beta_x != beta_y) the residual left, the discrete slip, is not along the traction, and the
// direction carries the filters' memories even under constant input, where the time term
// vanishes: the fixed point moved with h beta, i.e. with the step length. A residual along the
// traction (Coulomb) is tau_i = rhs_i / (1 + h beta_i + lambda), lambda >= 0 putting |tau| on g:
// a root search per node, several times the march's own work at a slipping node. Here lambda
// comes from the steady part: where tau_old is the traction itself on the bound, tau (1 + lambda)
// = v, so 1 + lambda = v . (r tau_old) / g^2, exact at a fixed point (under constant input the
// march settles on steady FastSim's traction at any step length), without a square root; lambda
// is held at 0 (the guess's direction) where that product says the traction turned. With beta_x
// = beta_y the direction is the guess's whatever lambda. The result is put on the bound as
// StripSums::node does.
[[gnu::always_inline]] inline bool slipsAlongTheResidual(const PackedStep& m, const Pair& history,
                                                         const Pair& old, const Pair& upstreamOld,
                                                         double g, double* tx, double* ty) {
  const double t2 = *tx * *tx + *ty * *ty;
  if (!(t2 > g * g) || !(t2 > 1e-300)) return false;  // adhesion, or StripSums::node's tiny path
  // v = rhs - h beta r tau_old = (guess - memory tau_old) / decay, the guess being history + decay
  // tau_up; tau_up is taken as the upstream node's old traction (r times), equal to it at a fixed
  // point, so that v and lambda, off the march's serial chain through tau_up, add no latency to
  // it. tau_i is along guess_i / (1 + lambda decay_i), i.e. along guess_i w_i with w_i = g^2 (1 +
  // lambda decay_j), j the other direction: times both denominators and g^2, no division.
  // r v . tau_old, with r v = (history - memory tau_old) r / decay + r^2 upstreamOld.
  const Pair rSteady =
      (history - m.memory * old) * m.scaledInverseDecay + m.squaredScale * upstreamOld;
  const double g2 = g * g, excess = std::max((rSteady * old).sum() - g2, 0.0);
  const Pair w = g2 + excess * m.decaySwapped;
  const Pair d = Pair(*tx, *ty) * w;
  const double d2 = (d * d).sum();
  // A bound next to zero, or so large that d2 leaves the doubles: StripSums::node's way.
  if (!(d2 > 1e-300) || !(d2 < 1e300)) return false;
  const Pair t = d * (g / std::sqrt(d2));
  *tx = t(0);
  *ty = t(1);
  return true;
}

// One strip of the march: where its history starts, its running traction and sums, and its two
// steps (from the patch's leading edge to the first loaded node, and between nodes).
template <bool kSecond, bool kResidualAlongTraction, class Source>
struct StripMarch {
  static constexpr bool kMapped = Source::kMapped;
  const double* history;  // Source::strip
  PackedStep entry, full;
  int first, enter, leave;  // the strip's node 0; its loaded nodes [enter, leave)
  double tx = 0.0, ty = 0.0;
  Pair oldUpstream = Pair::Zero();  // the last node's old traction (slipsAlongTheResidual)
  StripSums sums = {};
  [[gnu::always_inline]] void node(int k, const PackedStep& m, const Source& source,
                                   const double* xn, const FieldPointers& out,
                                   const StateUpdate<kSecond>& update) {
    step(k, m, source.template at<kSecond>(history, k - first), xn, out, update);
  }
  // Node k from its history o (read by the caller).
  [[gnu::always_inline]] void step(int k, const PackedStep& m, const History& o, const double* xn,
                                   const FieldPointers& out, const StateUpdate<kSecond>& update) {
    const Pair &old = o.t, &s = o.s;
    // The upstream traction enters last: it is the only operand on the march's serial chain.
    Pair guess = m.memory * old - m.lag * s - m.push;  // PackedStep's history
    if constexpr (kResidualAlongTraction) guess(0) -= m.coupleX * oldUpstream(1);
    tx = guess(0) + m.decayX * tx;
    ty = (guess(1) - m.pushPerXn * xn[k]) + m.decayY * ty;
    if constexpr (kResidualAlongTraction) {
      const Pair own(guess(0), guess(1) - m.pushPerXn * xn[k]), upstreamOld = oldUpstream;
      oldUpstream = old;
      if (slipsAlongTheResidual(m, own, old, upstreamOld, out.bound[k], &tx, &ty)) {
        sums.add(k, xn[k], out.bound[k], true, tx, ty, out);
        update(k, Pair(tx, ty), o);
        return;
      }
    }
    sums.node(k, xn[k], out.bound[k], &tx, &ty, out);
    update(k, Pair(tx, ty), o);
  }
};

// Every strip's nodes outside the patch (a fixed mesh larger than it), in one pass before the
// march: the bound is zero there, so whatever the march would bring saturates at zero; only the
// filter state moves. The constants and pointers are copied into locals first: read through
// references, they were reloaded after every store (a double or bool store may alias them).
// outsideFrom[j]: strip j's outside nodes before it at either end are not taken (held decayed, see
// TransientStorage::lazyBefore); 0 takes them all.
template <bool kSecond, class Source>
void unloadedNodes(const PatchMesh& mesh, const std::vector<StripEntry>& entries,
                   const int* outsideFrom, const Source& source, const FieldPointers& field,
                   const StateUpdate<kSecond>& updateRef) {
  const StateUpdate<kSecond> update = updateRef;
  const FieldPointers out = field;
  const int nx = mesh.nx();
  auto nodes = [&](const double* strip, int first, int from, int to) {
    for (int i = from; i < to; ++i) {
      update(first + i, Pair(0.0, 0.0), source.template at<kSecond>(strip, i));
      out.unloaded(first + i);
    }
  };
  for (int j = 0; j < mesh.ny(); ++j) {
    const int first = mesh.index(0, j), enter = std::min(entries[j].first, nx);
    const double* const strip = source.strip(j, nx);
    nodes(strip, first, outsideFrom[j], std::min(enter, nx - outsideFrom[j]));
    nodes(strip, first, std::max(nx - enter, enter), nx - outsideFrom[j]);
  }
}

// One step's arguments (transientFastSim's): carried where `map` is set, reading `previous`.
struct TransientStep {
  const PatchMesh& mesh;
  const Flexibilities& L;
  const Creepages& c;
  double V, dt;
  const FilterZ &zx, &zy;
  double historyScale;
  const AlongStripMap* map;
  const TransientState* previous;
  TransientState* st;
  TractionField* f;
  bool second;  // march s2 (a second-order filter, or marchSecond)
};

// A step's constants and a strip's march from them (its node and history source).
template <bool kSecond, bool kResidualAlongTraction, class Source>
struct TransientMarch {
  using Strip = StripMarch<kSecond, kResidualAlongTraction, Source>;
  const PatchMesh& mesh;
  TransientState* st;
  TractionField* f;
  Source history;
  double r;
  TimeTerm X, Y;
  StateUpdate<kSecond> update;
  Pair beta;
  LateralDrive drive;
  double gx, gphiX, a, coupling;
  const double* xn;
  FieldPointers out;
  int nx, ny;
  TransientMarch(const TransientStep& s, Source source)
      : mesh(s.mesh),
        st(s.st),
        f(s.f),
        history(source),
        r(s.historyScale),
        X(s.zx, s.V, s.dt, r),
        Y(s.zy, s.V, s.dt, r),
        update(X, Y, s.zx, s.zy, s.dt, r, s.st),
        beta(X.beta, Y.beta),
        drive(lateralDrive(s.L, s.c)),
        gx(s.c.xi / s.L.L1),
        gphiX(s.c.phi / s.L.spinX()),
        a(s.mesh.a()),
        coupling(s.L.lateralCoupling),
        xn(s.mesh.xNorms().data()),
        out(s.f),
        nx(s.mesh.nx()),
        ny(s.mesh.ny()) {
    history.writesTo(*st);
  }
  // Strip j's march: its history, both steps' constants and its loaded nodes.
  [[gnu::always_inline]] Strip strip(int j) const {
    const StripDrives d(mesh, j, gx, gphiX, coupling);
    const StripEntry e = f->entry[j];
    const int first = mesh.index(0, j);
    return Strip{history.strip(j, nx),
                 PackedStep(beta, X.lagPerLength, r, e.h, d.x, drive.gy, drive.gphi, a, d.perTy),
                 PackedStep(beta, X.lagPerLength, r, mesh.stripStep(j), d.x, drive.gy, drive.gphi,
                            a, d.perTy),
                 first,
                 first + e.first,
                 first + nx - e.first};
  }
  // The nodes outside the patch do not touch the loaded ones: they go first, in a pass of their
  // own.
  void outside() const {
    unloadedNodes(mesh, f->entry, TransientStorage::outsideFrom(*st), history, out, update);
  }
};

}  // namespace transient
}  // namespace wheel_rail_contact
