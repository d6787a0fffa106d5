#include "core/fastsim/transient_fastsim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

// The four-strip march needs x86's AVX (chosen at run time); elsewhere only the two-strip march.
#include "core/fastsim/avx_lanes.hpp"

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

namespace {

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
// PackedStep's arguments that differ by strip, taken alike by the two-strip march and the lanes.
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
Pair pairAt(const double* p) {
  return Eigen::Map<const Pair, Eigen::Aligned16>(p);
}
void storePair(double* p, const Pair& v) {
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
  // Node i of two strips (CarriedHistory's interface; the march only takes it for a mapped source).
  template <bool kSecond>
  void atBoth(const double* a, const double* b, int i, History* ha, History* hb) const {
    *ha = at<kSecond>(a, i);
    *hb = at<kSecond>(b, i);
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
  // Node i of two strips, the map's offset and weights read once for both (the slip flags'
  // stores between two reads would have the compiler read them again).
  template <bool kSecond>
  [[gnu::always_inline]] void atBoth(const double* a, const double* b, int i, History* ha,
                                     History* hb) const {
    const std::ptrdiff_t o = offsets[i];
    const Pair w0 = pairAt(weights + 4 * i), w1 = pairAt(weights + 4 * i + 2);
    auto read = [&](const double* strip, int offset) __attribute__((always_inline))->Pair {
      const double* p = strip + o + offset;
      return w0 * pairAt(p) + w1 * pairAt(p + kPerNode);
    };
    *ha = {read(a, kTraction), read(a, kState), kSecond ? read(a, kSecondState) : Pair()};
    *hb = {read(b, kTraction), read(b, kState), kSecond ? read(b, kSecondState) : Pair()};
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

#ifdef WRC_FOUR_STRIP_LANES
// Four strips of the residual-along-traction march at once, one in each lane of AVX registers:
// StripMarch::step's arithmetic, operation for operation (no fused multiply-add), so each strip's
// result is that of one strip at a time, bit for bit. The lanes are strips, not the (x, y) pair of
// one node: one instruction then does four strips' work at a node, the slip return and the
// running traction's chain included. The strips go in groups of four of about the same length
// (strips of a fixed mesh differ in length); a lane whose strip ends repeats one still marching. A
// node where a lane meets a tiny traction or a slip return out of range (slipsAlongTheResidual's
// guards) stops the lanes; the caller takes it one strip at a time.
// Compiled for AVX, called only where the CPU has it (fourStripLanesAvailable); elsewhere the march
// goes two strips at a time.
namespace quad {

using namespace avx;

// The x and the y lanes of the four (x, y) pairs at p[q] + offset.
WRC_AVX_INLINE void split(const double* const* p, int offset, V* x, V* y) {
  const V ac = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_load_pd(p[0] + offset)),
                                    _mm_load_pd(p[2] + offset), 1);
  const V bd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_load_pd(p[1] + offset)),
                                    _mm_load_pd(p[3] + offset), 1);
  *x = _mm256_unpacklo_pd(ac, bd);
  *y = _mm256_unpackhi_pd(ac, bd);
}
// The same from four Histories' member m.
WRC_AVX_INLINE void split(const History* h, Pair History::*m, V* x, V* y) {
  const double* const p[4] = {(h[0].*m).data(), (h[1].*m).data(), (h[2].*m).data(),
                              (h[3].*m).data()};
  split(p, 0, x, y);
}
// The lanes' history at node i of the march: traction, filter state and (second order) second
// state, x and y apart. p[q]: where lane q's node is written.
// In place: read where it is written.
struct InPlaceReader {
  template <bool kSecond, int>
  WRC_AVX_INLINE void read(int, const double* const* p, V* h) const {
    split(p, kTraction, &h[0], &h[1]);
    split(p, kState, &h[2], &h[3]);
    if constexpr (kSecond) split(p, kSecondState, &h[4], &h[5]);
  }
};
// Carried (CarriedHistory) where the four lanes march the same node `at` + i of their strips: the
// map's offset and weights are the lanes' own, w0 v0 + w1 v1 as CarriedHistory::carried.
struct CarriedReader {
  const std::ptrdiff_t* offsets;
  const double* weights;
  const double* strip[4];  // the old strips' node 0
  int at;
  template <bool kSecond, int kLive>
  WRC_AVX_INLINE void read(int i, const double* const*, V* h) const {
    const std::ptrdiff_t o = offsets[at + i];
    const V w0 = _mm256_set1_pd(weights[4 * (at + i)]),
            w1 = _mm256_set1_pd(weights[4 * (at + i) + 2]);
    // Per lane the node's traction and filter state together, (tx, ty, sx, sy), carried as one
    // register, then turned into the lanes' tx, ty, sx, sy; s2 as a pair per lane.
    V r[4];
    for (int q = 0; q < 4; ++q) {
      const double* const p = strip[std::min(q, kLive - 1)] + o;
      r[q] = add(mul(w0, _mm256_loadu_pd(p)), mul(w1, _mm256_loadu_pd(p + kPerNode)));
    }
    const V a = _mm256_unpacklo_pd(r[0], r[1]), b = _mm256_unpackhi_pd(r[0], r[1]),
            c = _mm256_unpacklo_pd(r[2], r[3]), d = _mm256_unpackhi_pd(r[2], r[3]);
    h[0] = _mm256_permute2f128_pd(a, c, 0x20);
    h[1] = _mm256_permute2f128_pd(b, d, 0x20);
    h[2] = _mm256_permute2f128_pd(a, c, 0x31);
    h[3] = _mm256_permute2f128_pd(b, d, 0x31);
    if constexpr (kSecond) {
      const __m128d v0 = _mm256_castpd256_pd128(w0), v1 = _mm256_castpd256_pd128(w1);
      __m128d e[4];
      for (int q = 0; q < 4; ++q) {
        const double* const p = strip[std::min(q, kLive - 1)] + o + kSecondState;
        e[q] =
            _mm_add_pd(_mm_mul_pd(v0, _mm_load_pd(p)), _mm_mul_pd(v1, _mm_load_pd(p + kPerNode)));
      }
      const V ac = _mm256_insertf128_pd(_mm256_castpd128_pd256(e[0]), e[2], 1),
              bd = _mm256_insertf128_pd(_mm256_castpd128_pd256(e[1]), e[3], 1);
      h[4] = _mm256_unpacklo_pd(ac, bd);
      h[5] = _mm256_unpackhi_pd(ac, bd);
    }
  }
};
// Any other: read(i, h) gives the four lanes' Histories.
template <class Read>
struct HistoryReader {
  Read read_;
  template <bool kSecond, int>
  WRC_AVX_INLINE void read(int i, const double* const*, V* h) const {
    History n[4];
    read_(i, n);
    split(n, &History::t, &h[0], &h[1]);
    split(n, &History::s, &h[2], &h[3]);
    if constexpr (kSecond) split(n, &History::s2, &h[4], &h[5]);
  }
};

// The first kLive of the four (x, y) pairs into p[q] + offset.
template <int kLive>
WRC_AVX_INLINE void join(V x, V y, double* const* p, int offset) {
  const V ac = _mm256_unpacklo_pd(x, y), bd = _mm256_unpackhi_pd(x, y);
  _mm_store_pd(p[0] + offset, _mm256_castpd256_pd128(ac));
  if constexpr (kLive > 1) _mm_store_pd(p[1] + offset, _mm256_castpd256_pd128(bd));
  if constexpr (kLive > 2) _mm_store_pd(p[2] + offset, _mm256_extractf128_pd(ac, 1));
  if constexpr (kLive > 3) _mm_store_pd(p[3] + offset, _mm256_extractf128_pd(bd, 1));
}
// The lanes' strips: per lane q its strip (index, node 0, history, end), next node and running
// state (StripMarch's tx, ty, oldUpstream, sums) as rows of four, and the PackedStep constants of
// its two steps (entry: from the patch's leading edge to its first loaded node; full: between
// nodes) as rows of four.
struct Lanes {
  enum Constant {
    kMemX,
    kMemY,
    kLagX,
    kLagY,
    kPushX,
    kPushY,
    kDecayX,
    kDecayY,
    kPushPerXn,
    kInverseX,
    kInverseY,
    kScale2,
    kCoupleX,
    kConstants
  };
  enum Running { kTx, kTy, kUpX, kUpY, kSumX, kSumY, kSumXnY, kLoaded, kStuck, kRunning };
  using Constants = double[kConstants][4];
  alignas(32) Constants entry, full;
  alignas(32) double v[kRunning][4];
  const double* history[4];  // Source::strip
  int strip[4], first[4], leave[4], next[4];
  StripSums sums(int q) const {
    StripSums s;
    s.tx = v[kSumX][q];
    s.ty = v[kSumY][q];
    s.xnTy = v[kSumXnY][q];
    s.stuck = static_cast<int>(v[kStuck][q]);
    s.loaded = static_cast<int>(v[kLoaded][q]);
    return s;
  }
  // Lane q's running state into strip s, and back.
  template <class Strip>
  void give(int q, Strip* s) const {
    s->tx = v[kTx][q];
    s->ty = v[kTy][q];
    s->oldUpstream = Pair(v[kUpX][q], v[kUpY][q]);
    s->sums = sums(q);
  }
  template <class Strip>
  void take(int q, const Strip& s) {
    const double vq[kRunning] = {
        s.tx,      s.ty,        s.oldUpstream(0),      s.oldUpstream(1),    s.sums.tx,
        s.sums.ty, s.sums.xnTy, double(s.sums.loaded), double(s.sums.stuck)};
    for (int r = 0; r < kRunning; ++r) v[r][q] = vq[r];
  }
};

// PackedStep's constants for four strips into c, lane q's for a step H[q], x drive driveX[q] and
// lateral coupling perTy[q]: PackedStep's arithmetic, operation for operation, so each lane holds
// its strip's PackedStep bit for bit.
WRC_AVX_INLINE void pack(V H, V driveX, V perTy, const Pair& beta, double lagPerLength, double r,
                         double gy, double gphi, double a, Lanes::Constants& c) {
  using L = Lanes;
  const V one = _mm256_set1_pd(1.0), R = _mm256_set1_pd(r);
  const V hbX = mul(H, _mm256_set1_pd(beta(0))), hbY = mul(H, _mm256_set1_pd(beta(1)));
  const V decayX = _mm256_div_pd(one, add(one, hbX)), decayY = _mm256_div_pd(one, add(one, hbY));
  store(c[L::kMemX], mul(mul(hbX, R), decayX));
  store(c[L::kMemY], mul(mul(hbY, R), decayY));
  store(c[L::kInverseX], mul(R, add(one, hbX)));
  store(c[L::kInverseY], mul(R, add(one, hbY)));
  store(c[L::kScale2], _mm256_set1_pd(r * r));
  const V lag = mul(H, _mm256_set1_pd(lagPerLength));
  store(c[L::kLagX], mul(lag, decayX));
  store(c[L::kLagY], mul(lag, decayY));
  store(c[L::kPushX], mul(mul(H, driveX), decayX));
  const V gphiV = _mm256_set1_pd(gphi);
  store(c[L::kPushY],
        mul(mul(H, add(_mm256_set1_pd(gy), mul(mul(_mm256_set1_pd(0.5), H), gphiV))), decayY));
  store(c[L::kDecayX], decayX);
  store(c[L::kDecayY], decayY);
  store(c[L::kPushPerXn], mul(mul(mul(H, gphiV), _mm256_set1_pd(a)), decayY));
  store(c[L::kCoupleX], mul(mul(mul(R, H), perTy), decayX));
}

// A group's start: lane q takes strip lanes->strip[q] of `mesh`, entering at entry[strip].h:
// both steps' constants (pack, on the strip's StripDrives), the running state zero. The per-strip
// values go into the lanes from registers and every row is written whole, so no load waits on
// stores of parts of it.
[[gnu::target("avx")]] void start(const PatchMesh& mesh, const StripEntry* entry, double gx,
                                  double gphiX, double coupling, const Pair& beta,
                                  double lagPerLength, double r, double gy, double gphi, double a,
                                  Lanes* lanes) {
  double h[4], step[4], driveX[4], perTy[4];
  for (int q = 0; q < 4; ++q) {
    const int j = lanes->strip[q];
    const StripDrives drives(mesh, j, gx, gphiX, coupling);
    h[q] = entry[j].h;
    step[q] = mesh.stripStep(j);
    driveX[q] = drives.x;
    perTy[q] = drives.perTy;
  }
  const V dx = _mm256_set_pd(driveX[3], driveX[2], driveX[1], driveX[0]),
          ty = _mm256_set_pd(perTy[3], perTy[2], perTy[1], perTy[0]);
  pack(_mm256_set_pd(h[3], h[2], h[1], h[0]), dx, ty, beta, lagPerLength, r, gy, gphi, a,
       lanes->entry);
  pack(_mm256_set_pd(step[3], step[2], step[1], step[0]), dx, ty, beta, lagPerLength, r, gy, gphi,
       a, lanes->full);
  for (auto& row : lanes->v) store(row, _mm256_setzero_pd());
}

// Every lane q not live[q] repeats lane p: the same strip, node, state and constants (rows
// written whole, as in start).
[[gnu::target("avx")]] void repeat(int p, const bool* live, Lanes* lanes) {
  const V dead = _mm256_castsi256_pd(
      _mm256_set_epi64x(live[3] ? 0 : -1, live[2] ? 0 : -1, live[1] ? 0 : -1, live[0] ? 0 : -1));
  for (auto& row : lanes->entry) store(row, select(dead, _mm256_broadcast_sd(row + p), load(row)));
  for (auto& row : lanes->full) store(row, select(dead, _mm256_broadcast_sd(row + p), load(row)));
  for (auto& row : lanes->v) store(row, select(dead, _mm256_broadcast_sd(row + p), load(row)));
  for (int q = 0; q < 4; ++q) {
    if (live[q]) continue;
    lanes->history[q] = lanes->history[p];
    lanes->strip[q] = lanes->strip[p];
    lanes->first[q] = lanes->first[p];
    lanes->leave[q] = lanes->leave[p];
    lanes->next[q] = lanes->next[p];
  }
}

// Nodes next[q] + i of the lanes' strips, i < n, on the step constants Lanes::full, the first on
// Lanes::entry where `entry` (the strips' first loaded nodes); read(i, h) gives their histories
// h[0..3]. Returns the number of nodes marched: n, or where the guards stopped the lanes; next
// advances by it. Lanes from kLive on repeat lane kLive - 1 (repeat): they read its history and
// write nothing (its stores are theirs).
template <bool kSecond, int kLive, class Reader>
[[gnu::target("avx"), gnu::noinline]] int march(Lanes* lanes, bool entry, int n,
                                                const Reader& reader, const double* xn,
                                                const FieldPointers& field,
                                                const StateUpdate<kSecond>& update) {
  using L = Lanes;
  const FieldPointers out = field;
  double* const written = update.written;
  // The step's constants: the entry step's at the first node where `entry`, then the full step's.
  V memX, memY, lagX, lagY, pushX, pushY, decayX, decayY, pushPerXn, inverseX, inverseY, scale2,
      coupleX;
  auto steps = [&](const Lanes::Constants& c) __attribute__((always_inline, target("avx"))) {
    memX = load(c[L::kMemX]);
    memY = load(c[L::kMemY]);
    lagX = load(c[L::kLagX]);
    lagY = load(c[L::kLagY]);
    pushX = load(c[L::kPushX]);
    pushY = load(c[L::kPushY]);
    decayX = load(c[L::kDecayX]);
    decayY = load(c[L::kDecayY]);
    pushPerXn = load(c[L::kPushPerXn]);
    inverseX = load(c[L::kInverseX]);
    inverseY = load(c[L::kInverseY]);
    scale2 = load(c[L::kScale2]);
    coupleX = load(c[L::kCoupleX]);
  };
  steps(entry ? lanes->entry : lanes->full);
  const V rateX = _mm256_set1_pd(update.rate(0)), rateY = _mm256_set1_pd(update.rate(1)),
          rateOldX = _mm256_set1_pd(update.rateOld(0)),
          rateOldY = _mm256_set1_pd(update.rateOld(1)),
          poleOldX = _mm256_set1_pd(update.poleOld(0)),
          poleOldY = _mm256_set1_pd(update.poleOld(1));
  // SecondStateUpdate's constants (unused by the first-order march).
  struct {
    V r, rateX, rateY, rateOldX, rateOldY, poleOldX, poleOldY;
  } second;
  if constexpr (kSecond) {
    const auto& q = update.second;
    second = {_mm256_set1_pd(q.r),           _mm256_set1_pd(q.rate2(0)),
              _mm256_set1_pd(q.rate2(1)),    _mm256_set1_pd(q.rate2Old(0)),
              _mm256_set1_pd(q.rate2Old(1)), _mm256_set1_pd(q.pole2Old(0)),
              _mm256_set1_pd(q.pole2Old(1))};
  }
  auto& v = lanes->v;
  V tx = load(v[L::kTx]), ty = load(v[L::kTy]), upX = load(v[L::kUpX]), upY = load(v[L::kUpY]),
    sumX = load(v[L::kSumX]), sumY = load(v[L::kSumY]), sumXnY = load(v[L::kSumXnY]),
    loaded = load(v[L::kLoaded]), stuck = load(v[L::kStuck]);
  const V one = _mm256_set1_pd(1.0);
  int next[4];
  for (int q = 0; q < 4; ++q) next[q] = lanes->next[std::min(q, kLive - 1)];
  int i = 0;
  for (; i < n; ++i) {
    const int node[4] = {next[0] + i, next[1] + i, next[2] + i, next[3] + i};
    // Node k's history is written at written + kPerNode k; in place it is read there too.
    double* const p[4] = {written + kPerNode * node[0], written + kPerNode * node[1],
                          written + kPerNode * node[2], written + kPerNode * node[3]};
    V h[6];  // oldX, oldY, sX, sY, s2X, s2Y
    reader.template read<kSecond, kLive>(i, p, h);
    const V oldX = h[0], oldY = h[1], sX = h[2], sY = h[3];
    const V guessX = sub(sub(sub(mul(memX, oldX), mul(lagX, sX)), pushX), mul(coupleX, upY));
    const V guessY = sub(sub(mul(memY, oldY), mul(lagY, sY)), pushY);
    const V x = at(xn, node), ownY = sub(guessY, mul(pushPerXn, x));
    const V nx = add(guessX, mul(decayX, tx)), ny = add(ownY, mul(decayY, ty));
    const V g = at(out.bound, node), g2 = mul(g, g);
    const V t2 = add(mul(nx, nx), mul(ny, ny));
    const V slips = greater(t2, g2);
    const int slipping = _mm256_movemask_pd(slips);
    V stop = outsideLanes(t2, g2);  // StripSums::node's tiny path: the lanes stop
    if (slipping == 0) {
      // All four in adhesion: the traction is the guess. A branch, not a select: the slip
      // return's square root and division would otherwise sit on the running traction's chain.
      if (_mm256_movemask_pd(stop) != 0) break;
      tx = nx;
      ty = ny;
    } else {
      // slipsAlongTheResidual in every lane, taken where the lane slips.
      const V rX = add(mul(sub(guessX, mul(memX, oldX)), inverseX), mul(scale2, upX));
      const V rY = add(mul(sub(ownY, mul(memY, oldY)), inverseY), mul(scale2, upY));
      const V excess =
          _mm256_max_pd(_mm256_setzero_pd(), sub(add(mul(rX, oldX), mul(rY, oldY)), g2));
      const V dX = mul(nx, add(g2, mul(excess, decayY)));
      const V dY = mul(ny, add(g2, mul(excess, decayX)));
      const V d2 = add(mul(dX, dX), mul(dY, dY));
      const V inRange = _mm256_and_pd(greater(d2, _mm256_set1_pd(1e-300)),
                                      _mm256_cmp_pd(d2, _mm256_set1_pd(1e300), _CMP_LT_OQ));
      stop = _mm256_or_pd(stop, _mm256_andnot_pd(inRange, slips));
      if (_mm256_movemask_pd(stop) != 0) break;
      const V scale = _mm256_div_pd(g, _mm256_sqrt_pd(d2));
      tx = select(slips, mul(dX, scale), nx);
      ty = select(slips, mul(dY, scale), ny);
    }
    upX = oldX;
    upY = oldY;
    // StripSums::add.
    scatter<kLive>(tx, out.tx, node);
    scatter<kLive>(ty, out.ty, node);
    storeFlags<kLive>(slipping, out.slip, node);
    sumX = add(sumX, tx);
    sumY = add(sumY, ty);
    sumXnY = add(sumXnY, mul(x, ty));
    const V pressed = greater(g, _mm256_setzero_pd());
    loaded = add(loaded, _mm256_and_pd(pressed, one));
    stuck = add(stuck, _mm256_and_pd(_mm256_andnot_pd(slips, pressed), one));
    // StateUpdate.
    V nextX = sub(sub(mul(rateX, tx), mul(rateOldX, oldX)), mul(poleOldX, sX));
    V nextY = sub(sub(mul(rateY, ty), mul(rateOldY, oldY)), mul(poleOldY, sY));
    if constexpr (kSecond) {
      const V s2X = h[4], s2Y = h[5];
      nextX = add(nextX, mul(second.r, s2X));
      nextY = add(nextY, mul(second.r, s2Y));
      join<kLive>(
          sub(sub(mul(second.rateX, tx), mul(second.rateOldX, oldX)), mul(second.poleOldX, sX)),
          sub(sub(mul(second.rateY, ty), mul(second.rateOldY, oldY)), mul(second.poleOldY, sY)), p,
          kSecondState);
    }
    join<kLive>(nextX, nextY, p, kState);
    join<kLive>(tx, ty, p, kTraction);
    if (i == 0 && entry) steps(lanes->full);
  }
  store(v[L::kTx], tx);
  store(v[L::kTy], ty);
  store(v[L::kUpX], upX);
  store(v[L::kUpY], upY);
  store(v[L::kSumX], sumX);
  store(v[L::kSumY], sumY);
  store(v[L::kSumXnY], sumXnY);
  store(v[L::kLoaded], loaded);
  store(v[L::kStuck], stuck);
  for (int q = 0; q < 4; ++q) lanes->next[q] += i;
  return i;
}

}  // namespace quad
#endif  // WRC_FOUR_STRIP_LANES

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

template <bool kSecond, bool kResidualAlongTraction, class Source>
CreepForces march(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c, double V,
                  double dt, const FilterZ& zx, const FilterZ& zy, double historyScale,
                  Source history, TransientState* st, TractionField* f) {
  const double r = historyScale;
  const TimeTerm X(zx, V, dt, r), Y(zy, V, dt, r);
  const StateUpdate<kSecond> update(X, Y, zx, zy, dt, r, st);
  history.writesTo(*st);
  const Pair beta(X.beta, Y.beta);
  const LateralDrive drive = lateralDrive(L, c);  // plain names: lambdas below capture them
  const double gx = c.xi / L.L1, gy = drive.gy, gphi = drive.gphi, gphiX = c.phi / L.spinX(),
               a = mesh.a();
  const double* const xn = mesh.xNorms().data();
  const FieldPointers out(f);
  const int nx = mesh.nx(), ny = mesh.ny();
  ForceSums sums;
  using Strip = StripMarch<kSecond, kResidualAlongTraction, Source>;
  // The nodes outside the patch do not touch the loaded ones: they go first, in a pass of their
  // own.
  unloadedNodes(mesh, f->entry, TransientStorage::outsideFrom(*st), history, out, update);
  // Strip j's march.
  auto strip = [&](int j) __attribute__((always_inline)) {
    const StripDrives d(mesh, j, gx, gphiX, L.lateralCoupling);
    const StripEntry e = f->entry[j];
    const int first = mesh.index(0, j), enter = first + e.first, leave = first + nx - e.first;
    const double* const stripHistory = history.strip(j, nx);
    return Strip{stripHistory,
                 PackedStep(beta, X.lagPerLength, r, e.h, d.x, gy, gphi, a, d.perTy),
                 PackedStep(beta, X.lagPerLength, r, mesh.stripStep(j), d.x, gy, gphi, a, d.perTy),
                 first,
                 enter,
                 leave};
  };
  auto finish = [&](int j, const Strip& s) {
    sums.addStrip(mesh, j, s.sums, f->entry[j], out.tx, out.ty);
  };
  // Two strips at a time: their marches are independent serial chains, so each fills the other's
  // latency. Each strip's nodes still go in order: the result is that of one strip at a time.
  auto marchTwo = [&](Strip & A, Strip & B) __attribute__((always_inline)) {
    int ka = A.enter, kb = B.enter;
    // The first loaded node steps from the patch's leading edge, where the traction is zero.
    if (ka < A.leave) A.node(ka++, A.entry, history, xn, out, update);
    if (kb < B.leave) B.node(kb++, B.entry, history, xn, out, update);
    const int n = std::max(0, std::min(A.leave - ka, B.leave - kb));
    const int i = ka - A.first;
    if (Source::kMapped && i == kb - B.first) {
      // On the adaptive mesh both strips march the same nodes of their strips: read the map once.
      for (int s = 0; s < n; ++s) {
        History ha, hb;
        history.template atBoth<kSecond>(A.history, B.history, i + s, &ha, &hb);
        A.step(ka + s, A.full, ha, xn, out, update);
        B.step(kb + s, B.full, hb, xn, out, update);
      }
    } else {
      for (int s = 0; s < n; ++s) {
        A.node(ka + s, A.full, history, xn, out, update);
        B.node(kb + s, B.full, history, xn, out, update);
      }
    }
    for (ka += n; ka < A.leave; ++ka) A.node(ka, A.full, history, xn, out, update);
    for (kb += n; kb < B.leave; ++kb) B.node(kb, B.full, history, xn, out, update);
  };
  auto marchOne = [&](Strip & A) __attribute__((always_inline)) {
    if (A.enter < A.leave) A.node(A.enter, A.entry, history, xn, out, update);
    for (int k = A.enter + 1; k < A.leave; ++k) A.node(k, A.full, history, xn, out, update);
  };
  int j = 0;
#ifdef WRC_FOUR_STRIP_LANES
  if constexpr (kResidualAlongTraction) {
    if (st->marchesFourStrips(nx) && ny >= 4) {
      // Four strips at a time in AVX's lanes (quad::march). The strips go in groups of four in
      // centre-out order: on a fixed mesh a strip's loaded length falls with |y|, so a group's
      // strips are about as long, and on the adaptive mesh all are. A group's constants are set
      // up in the lanes (quad::start), its first loaded nodes marched in them; a lane whose strip
      // ends repeats one that still marches (the same values to the same nodes; its sums unused).
      // A strip left over alone goes as a scalar. The strips' sums are added in strip order at the
      // end.
      StripSums* const stripSums = TransientStorage::stripSums(ny, st);
      quad::Lanes lanes;
      bool live[4];
      // n nodes of every lane, the first on the strips' entry steps where entryFirst, the nodes
      // the guards stop at one strip at a time.
      auto marchLanes = [&](bool entryFirst, int n, int own) {
        // The lanes live: the first `prefix`, the others repeating the last of them (own), or all
        // four marched where a dead lane sits between live ones.
        int prefix = 0;
        while (prefix < 4 && live[prefix]) ++prefix;
        for (int q = prefix; q < 4; ++q)
          if (live[q]) prefix = 4;
        int done = 0;
        auto run = [&](bool entry, const auto& reader) __attribute__((always_inline)) {
          const int m = n - done;
          switch (prefix) {
            case 1:
              return quad::march<kSecond, 1>(&lanes, entry, m, reader, xn, out, update);
            case 2:
              return quad::march<kSecond, 2>(&lanes, entry, m, reader, xn, out, update);
            case 3:
              return quad::march<kSecond, 3>(&lanes, entry, m, reader, xn, out, update);
            default:
              return quad::march<kSecond, 4>(&lanes, entry, m, reader, xn, out, update);
          }
        };
        while (done < n) {
          const bool entry = entryFirst && done == 0;
          if constexpr (Source::kMapped) {
            const int at0 = lanes.next[0] - lanes.first[0];
            bool aligned = true;  // the four march the same nodes of their strips
            for (int q = 1; q < 4; ++q) aligned = aligned && lanes.next[q] - lanes.first[q] == at0;
            if (aligned) {
              const quad::CarriedReader reader{
                  history.offsets,
                  history.weights,
                  {lanes.history[0], lanes.history[1], lanes.history[2], lanes.history[3]},
                  at0};
              done += run(entry, reader);
            } else {
              int from[4];
              for (int q = 0; q < 4; ++q) from[q] = lanes.next[q] - lanes.first[q];
              auto read = [&](int i, History* h) __attribute__((always_inline)) {
                for (int q = 0; q < 4; ++q)
                  h[q] = history.template at<kSecond>(lanes.history[q], from[q] + i);
              };
              done += run(entry, quad::HistoryReader<decltype(read)>{read});
            }
          } else {
            done += run(entry, quad::InPlaceReader{});
          }
          if (done == n) break;
          // The node the guards stopped at, one strip at a time (its constants as the lanes',
          // bit for bit).
          for (int q = 0; q < 4; ++q) {
            if (!live[q]) continue;
            Strip s = strip(lanes.strip[q]);
            lanes.give(q, &s);
            s.node(lanes.next[q], entry ? s.entry : s.full, history, xn, out, update);
            lanes.take(q, s);
            ++lanes.next[q];
          }
          quad::repeat(own, live, &lanes);
          ++done;
        }
      };
      for (int k = 0; k < ny;) {
        int count = 0;
        for (; k < ny && count < 4; ++k) {
          const int jk = mesh.centreOutStrip(k), e = f->entry[jk].first;
          if (e >= nx - e) {  // nothing loaded
            stripSums[jk] = StripSums{};
            continue;
          }
          lanes.strip[count] = jk;
          lanes.first[count] = mesh.index(0, jk);
          lanes.next[count] = lanes.first[count] + e;
          lanes.leave[count] = lanes.first[count] + nx - e;
          lanes.history[count] = history.strip(jk, nx);
          live[count] = true;
          ++count;
        }
        if (count == 0) break;
        // The last, outermost one or two strips as scalars: a node-row of the lanes costs about
        // what it costs with four live lanes, and takes the slip return's chain, as long as a
        // scalar pair's.
        if (count == 1) {
          Strip A = strip(lanes.strip[0]);
          marchOne(A);
          stripSums[lanes.strip[0]] = A.sums;
          break;
        }
        if (count == 2) {
          Strip A = strip(lanes.strip[0]), B = strip(lanes.strip[1]);
          marchTwo(A, B);
          stripSums[lanes.strip[0]] = A.sums;
          stripSums[lanes.strip[1]] = B.sums;
          break;
        }
        for (int q = count; q < 4; ++q) {  // the group's last lanes repeat its last strip
          lanes.strip[q] = lanes.strip[count - 1];
          lanes.first[q] = lanes.first[count - 1];
          lanes.next[q] = lanes.next[count - 1];
          lanes.leave[q] = lanes.leave[count - 1];
          lanes.history[q] = lanes.history[count - 1];
          live[q] = false;
        }
        quad::start(mesh, f->entry.data(), gx, gphiX, L.lateralCoupling, beta, X.lagPerLength, r,
                    gy, gphi, a, &lanes);
        // The first loaded node steps from the patch's leading edge, where the traction is zero.
        for (bool entry = true;; entry = false) {
          int n = std::numeric_limits<int>::max(), own = -1;
          bool ended = false;  // a lane's strip ended: the lanes repeating it must move on
          for (int q = 0; q < 4; ++q) {
            if (!live[q]) continue;
            if (lanes.next[q] == lanes.leave[q]) {
              stripSums[lanes.strip[q]] = lanes.sums(q);
              live[q] = false;
              ended = true;
            } else {
              n = std::min(n, lanes.leave[q] - lanes.next[q]);
              own = q;
            }
          }
          if (own < 0) break;
          if (ended) quad::repeat(own, live, &lanes);
          marchLanes(entry, n, own);
        }
      }
      for (int jj = 0; jj < ny; ++jj)
        sums.addStrip(mesh, jj, stripSums[jj], f->entry[jj], out.tx, out.ty);
      return sums.forces();
    }
  }
#endif
  for (; j + 1 < ny; j += 2) {
    Strip A = strip(j), B = strip(j + 1);
    marchTwo(A, B);
    finish(j, A);
    finish(j + 1, B);
  }
  for (; j < ny; ++j) {
    Strip A = strip(j);
    marchOne(A);
    finish(j, A);
  }
  return sums.forces();
}

// The march with the saturation `st` asks for (TransientState::Saturation), chosen once a step:
// the classic march carries no test of it per node.
template <bool kSecond, class Source>
CreepForces marchSaturating(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                            double V, double dt, const FilterZ& zx, const FilterZ& zy,
                            double historyScale, Source history, TransientState* st,
                            TractionField* f) {
  if (st->saturation() == TransientState::Saturation::kResidualAlongTraction)
    return march<kSecond, true>(mesh, L, c, V, dt, zx, zy, historyScale, history, st, f);
  return march<kSecond, false>(mesh, L, c, V, dt, zx, zy, historyScale, history, st, f);
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

bool TransientState::marchesFourStrips(int nx) const {
  switch (fourStripLanes_) {
    case FourStripLanes::kOff:
      return false;
    case FourStripLanes::kOn:
      return fourStripLanesAvailable();
    case FourStripLanes::kAuto:
      break;
  }
  return nx >= kFourStripLanesFromNodes && fourStripLanesAvailable();
}

CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, TransientState* st, TractionField* f,
                             bool marchSecond) {
  if (marchSecond || zx.secondOrder() || zy.secondOrder()) {
    TransientStorage::eager(mesh.ny(), st);  // the second-order march reads every node as it is
    return marchSaturating<true>(mesh, L, c, V, dt, zx, zy, historyScale, InPlace{}, st, f);
  }
  // Outside the patch the traction is zero and s <- -poleOld s, i.e. d = -a1 r (TimeTerm).
  const Pair d(-zx.a1 * historyScale, -zy.a1 * historyScale);
  const bool lazy = TransientStorage::lazyBefore(mesh, f->entry, d, st, f);
  const CreepForces forces =
      marchSaturating<false>(mesh, L, c, V, dt, zx, zy, historyScale, InPlace{}, st, f);
  if (lazy) TransientStorage::lazyAfter(mesh, f->entry, d, st);
  return forces;
}

CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, const AlongStripMap& map,
                             const TransientState& previous, TransientState* st, TractionField* f,
                             bool marchSecond) {
  TransientStorage::writtenInFull(mesh.ny(), st);
  const CarriedHistory carried(map, previous);  // reads `previous` materialized
  if (marchSecond || zx.secondOrder() || zy.secondOrder())
    return marchSaturating<true>(mesh, L, c, V, dt, zx, zy, historyScale, carried, st, f);
  return marchSaturating<false>(mesh, L, c, V, dt, zx, zy, historyScale, carried, st, f);
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

}  // namespace wheel_rail_contact
