// The marches' vector path (strip_lanes.hpp) in Highway's portable vector operations. This file is
// compiled once per Highway target (hwy/foreach_target.h): the baseline, where there are no lanes,
// and AVX2, where four strips go in the lanes of a 256-bit register; the dispatch at the end picks
// the best of them this CPU has, once (HWY_DYNAMIC_DISPATCH). The other x86 targets are left out
// (HWY_DISABLED_TARGETS): SSE4 would hold two strips a register and AVX-512 the same four, each a
// second vector path to test and to compile; a CPU without AVX2 runs the scalar reference.
#include "core/fastsim/strip_lanes.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/fastsim/steady_march.hpp"
#include "core/fastsim/transient_march.hpp"

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4 | HWY_AVX3 | HWY_AVX3_DL)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/fastsim/strip_lanes.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wheel_rail_contact {
namespace HWY_NAMESPACE {

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::FixedTag<double, 4>;  // a strip a lane
using V = hn::Vec<D>;
using M = hn::Mask<D>;
constexpr int kLanes = 4;

// Lane q's value: v[q].
HWY_INLINE V load4(const double* v) {
  HWY_ALIGN const double a[kLanes] = {v[0], v[1], v[2], v[3]};
  return hn::Load(D(), a);
}
// v[k[q]] in lane q.
HWY_INLINE V at(const double* v, const int* k) {
  HWY_ALIGN const double a[kLanes] = {v[k[0]], v[k[1]], v[k[2]], v[k[3]]};
  return hn::Load(D(), a);
}
// Lane q of v into v0[k[q]].
HWY_INLINE void scatter(V v, double* v0, const int* k) {
  HWY_ALIGN double a[kLanes];
  hn::Store(v, D(), a);
  for (int q = 0; q < kLanes; ++q) v0[k[q]] = a[q];
}
// Byte q of kFlagBytes[m] is bit q of m: four flags from a mask's bits.
constexpr uint32_t kFlagBytes[16] = {
    0x00000000, 0x00000001, 0x00000100, 0x00000101, 0x00010000, 0x00010001, 0x00010100, 0x00010101,
    0x01000000, 0x01000001, 0x01000100, 0x01000101, 0x01010000, 0x01010001, 0x01010100, 0x01010101};
// Lane q's flag into flags[k[q]].
HWY_INLINE void storeFlags(M m, bool* flags, const int* k) {
  uint8_t bits[8];
  hn::StoreMaskBits(D(), m, bits);
  const uint32_t bytes = kFlagBytes[bits[0]];
  for (int q = 0; q < kLanes; ++q) {
    const auto flag = static_cast<uint8_t>(bytes >> (8 * q));
    std::memcpy(flags + k[q], &flag, 1);  // a bool's byte, 0 or 1
  }
}
// Where StripSums::node's tiny path (|t|^2 = t2 not above 1e-300, or NaN: |t| measured by hypot)
// could differ from the lanes' t2 > g^2: a tiny or NaN t2 next to a bound not far above it. Where
// the bound is far above (g2 > 1e-290) the tiny path keeps the traction, as the lanes do.
HWY_INLINE M outsideLanes(V t2, V g2) {
  const D d;
  const V tinyT2 = hn::Set(d, 1e-300);
  const M tiny = hn::Not(hn::Gt(t2, tinyT2));  // NaN too
  const M keeps = hn::And(hn::Le(t2, tinyT2), hn::Gt(g2, hn::Set(d, 1e-290)));
  return hn::AndNot(keeps, tiny);
}
HWY_INLINE bool any(M m) {
  return !hn::AllFalse(D(), m);
}

// ---- steady FastSim ---------------------------------------------------------------------------

// Four strips of the steady march at once, one in each lane: SteadyStrip's node. Lane q marches
// nodes from[q] + i of strip S[q], i < n, all steps of a whole element (the strips' first nodes,
// half an element from the leading edge, go one strip at a time). Returns the nodes marched: n, or
// fewer where a lane met StripSums::node's tiny path (outsideLanes), which the caller then takes
// one strip at a time; S and from follow.
template <bool kCoupled>
HWY_NOINLINE int steadyLanes(steady::SteadyStrip<kCoupled>* S, int* from, int n, const double* xn,
                             const FieldPointers& field) {
  const D d;
  const FieldPointers out = field;
  double v[12][kLanes];  // the strips' constants and running values, row by row
  for (int q = 0; q < kLanes; ++q) {
    const steady::SteadyStrip<kCoupled>& s = S[q];
    v[0][q] = s.dx;
    v[1][q] = s.aj;
    v[2][q] = s.sx;
    if constexpr (kCoupled) v[3][q] = s.perTy;
    v[4][q] = s.tx;
    v[5][q] = s.ty;
    v[6][q] = s.sums.tx;
    v[7][q] = s.sums.ty;
    v[8][q] = s.sums.xnTy;
    v[9][q] = from[q] + 0.5;  // (i + 0.5), exact in doubles as UpstreamStep's
  }
  const V dx = load4(v[0]), aj = load4(v[1]), dxSx = hn::Mul(dx, load4(v[2]));
  V dxPerTy = hn::Zero(d);
  if constexpr (kCoupled) dxPerTy = hn::Mul(dx, load4(v[3]));
  const V halfDx = hn::Mul(hn::Set(d, 0.5), dx), gy = hn::Set(d, S[0].gy),
          gphi = hn::Set(d, S[0].gphi), one = hn::Set(d, 1.0), zero = hn::Zero(d);
  V tx = load4(v[4]), ty = load4(v[5]);
  // The strips' sums go on from where they are, in node order, as one strip at a time.
  V sumX = load4(v[6]), sumY = load4(v[7]), sumXnY = load4(v[8]), loaded = zero, stuck = zero;
  V iMid = load4(v[9]);
  const int k0[kLanes] = {S[0].k0 + from[0], S[1].k0 + from[1], S[2].k0 + from[2],
                          S[3].k0 + from[3]};
  int i = 0;
  for (; i < n; ++i) {
    const int k[kLanes] = {k0[0] + i, k0[1] + i, k0[2] + i, k0[3] + i};
    const V xMid = hn::Add(hn::NegMulAdd(iMid, dx, aj), halfDx);
    V nx = hn::Sub(tx, dxSx);
    if constexpr (kCoupled) nx = hn::NegMulAdd(dxPerTy, ty, nx);
    V ny = hn::NegMulAdd(dx, hn::MulAdd(gphi, xMid, gy), ty);
    const V g = at(out.bound, k), g2 = hn::Mul(g, g);
    const V t2 = hn::MulAdd(nx, nx, hn::Mul(ny, ny));
    if (any(outsideLanes(t2, g2))) break;
    const M slips = hn::Gt(t2, g2);
    if (any(slips)) {  // a branch: in adhesion the square root and division stay off the chain
      const V scale = hn::Div(g, hn::Sqrt(t2));
      nx = hn::IfThenElse(slips, hn::Mul(nx, scale), nx);
      ny = hn::IfThenElse(slips, hn::Mul(ny, scale), ny);
    }
    tx = nx;
    ty = ny;
    iMid = hn::Add(iMid, one);
    // StripSums::add.
    scatter(tx, out.tx, k);
    scatter(ty, out.ty, k);
    storeFlags(slips, out.slip, k);
    sumX = hn::Add(sumX, tx);
    sumY = hn::Add(sumY, ty);
    sumXnY = hn::MulAdd(at(xn, k), ty, sumXnY);
    const M pressed = hn::Gt(g, zero);
    loaded = hn::Add(loaded, hn::IfThenElseZero(pressed, one));
    stuck = hn::Add(stuck, hn::IfThenElseZero(hn::AndNot(slips, pressed), one));
  }
  const V rows[7] = {tx, ty, sumX, sumY, sumXnY, loaded, stuck};
  for (int r = 0; r < 7; ++r) hn::StoreU(rows[r], d, v[r]);
  for (int q = 0; q < kLanes; ++q) {
    steady::SteadyStrip<kCoupled>& s = S[q];
    s.tx = v[0][q];
    s.ty = v[1][q];
    s.sums.tx = v[2][q];
    s.sums.ty = v[3][q];
    s.sums.xnTy = v[4][q];
    s.sums.loaded += static_cast<int>(v[5][q]);
    s.sums.stuck += static_cast<int>(v[6][q]);
    from[q] += i;
  }
  return i;
}

// The steady march in lanes, four strips at a time in centre-out order (PatchMesh::centreOutStrip):
// on a mesh larger than the patch a group's strips are then about as long, and the lanes march
// most of their nodes together. A strip with no loaded node is only finished; two or three left
// over at the edges go in the lanes too (the lanes past them repeating the last), one alone one
// strip at a time, as do a group's first nodes and what its longer strips have left. The sums are
// added in strip order at the end, as one strip at a time.
template <bool kCoupled>
CreepForces steadyInLanes(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                          TractionField* f) {
  const steady::SteadyMarch<kCoupled> m(mesh, L, c, f);
  using Strip = steady::SteadyStrip<kCoupled>;
  const FieldPointers out = m.out;
  const double* const xn = m.xn;
  const int nx = m.nx, ny = m.ny;
  f->stripSums.resize(ny);
  StripSums* const stripSums = f->stripSums.data();
  for (int k = 0; k < ny;) {
    int js[kLanes], count = 0;
    for (; k < ny && count < kLanes; ++k) {
      const int j = mesh.centreOutStrip(k);
      if (!m.loaded(j)) {
        m.unloadedEnds(j);
        stripSums[j] = StripSums{};
        continue;
      }
      js[count++] = j;
    }
    Strip S[kLanes];
    int at[kLanes];
    for (int q = 0; q < count; ++q) {
      S[q] = m.strip(js[q]);
      at[q] = f->entry[js[q]].first;
    }
    if (count >= 2) {
      // Lanes past `count` repeat the last strip: the same values to the same nodes.
      auto repeatLast = [&] {
        for (int q = count; q < kLanes; ++q) {
          S[q] = S[count - 1];
          at[q] = at[count - 1];
        }
      };
      int n = std::numeric_limits<int>::max();
      for (int q = 0; q < count; ++q) {
        const StripEntry& e = f->entry[js[q]];
        S[q].node(at[q]++, e.h, xn, out);  // loaded: at least one node
        n = std::min(n, nx - e.first - at[q]);
      }
      repeatLast();
      while (n > 0) {
        n -= steadyLanes(S, at, n, xn, out);
        if (n == 0) break;
        for (int q = 0; q < count; ++q) S[q].node(at[q]++, S[q].dx, xn, out);  // the tiny path
        repeatLast();
        --n;
      }
    }
    for (int q = 0; q < count; ++q) {
      m.march(js[q], S[q], at[q]);
      m.unloadedEnds(js[q]);
      stripSums[js[q]] = S[q].sums;
    }
  }
  ForceSums sums;
  for (int j = 0; j < ny; ++j) sums.addStrip(mesh, j, stripSums[j], f->entry[j], out.tx, out.ty);
  return sums.forces();
}

CreepForces SteadyLanes(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                        TractionField* f) {
  if (L.lateralCoupling != 0.0) return steadyInLanes<true>(mesh, L, c, f);
  return steadyInLanes<false>(mesh, L, c, f);
}

// ---- the time-term march ----------------------------------------------------------------------

using transient::History;
using transient::kPerNode;
using transient::kSecondState;
using transient::kState;
using transient::kTraction;
using transient::Pair;
using transient::StateUpdate;

// The x and the y lanes of the four (x, y) pairs at p[q] + offset (16-byte aligned).
HWY_INLINE void split(const double* const* p, int offset, V* x, V* y) {
  const D d;
  const hn::Half<D> h;
  const V ac = hn::Combine(d, hn::Load(h, p[2] + offset), hn::Load(h, p[0] + offset));
  const V bd = hn::Combine(d, hn::Load(h, p[3] + offset), hn::Load(h, p[1] + offset));
  *x = hn::InterleaveLower(d, ac, bd);
  *y = hn::InterleaveUpper(d, ac, bd);
}
// The four (x, y) pairs into p[q] + offset.
HWY_INLINE void join(V x, V y, double* const* p, int offset) {
  const D d;
  const hn::Half<D> h;
  const V ac = hn::InterleaveLower(d, x, y), bd = hn::InterleaveUpper(d, x, y);
  hn::Store(hn::LowerHalf(h, ac), h, p[0] + offset);
  hn::Store(hn::LowerHalf(h, bd), h, p[1] + offset);
  hn::Store(hn::UpperHalf(h, ac), h, p[2] + offset);
  hn::Store(hn::UpperHalf(h, bd), h, p[3] + offset);
}

// The lanes' history at node i of the march: traction, filter state and (second order) second
// state, x and y apart, into h[0..5] (oldX, oldY, sX, sY, s2X, s2Y). p[q]: where lane q's node is
// written.
// In place: read where it is written.
struct InPlaceReader {
  template <bool kSecond>
  HWY_INLINE void read(int, const double* const* p, V* h) const {
    split(p, kTraction, &h[0], &h[1]);
    split(p, kState, &h[2], &h[3]);
    if constexpr (kSecond) split(p, kSecondState, &h[4], &h[5]);
  }
};
// Carried (transient::CarriedHistory): lane q reads node at[q] + i of its old strip, w0 v0 + w1 v1
// as CarriedHistory::carried. kAligned: the four lanes at the same node of their strips (the
// adaptive mesh's case), the map's offset and weights read once.
template <bool kAligned>
struct CarriedReader {
  const std::ptrdiff_t* offsets;
  const double* weights;
  const double* strip[kLanes];  // the old strips' node 0
  int at[kLanes];
  template <bool kSecond>
  HWY_INLINE void read(int i, const double* const*, V* h) const {
    const D d;
    const hn::Half<D> hd;
    // Per lane the node's traction and filter state together, (tx, ty, sx, sy), carried as one
    // register, then turned into the lanes' tx, ty, sx, sy; s2 as a pair per lane.
    V r[kLanes];
    hn::Vec<hn::Half<D>> e[kLanes];
    for (int q = 0; q < kLanes; ++q) {
      const int node = (kAligned ? at[0] : at[q]) + i;
      const double* const p = strip[q] + offsets[node];
      const V w0 = hn::Set(d, weights[4 * node]), w1 = hn::Set(d, weights[4 * node + 2]);
      r[q] = hn::MulAdd(w1, hn::LoadU(d, p + kPerNode), hn::Mul(w0, hn::LoadU(d, p)));
      if constexpr (kSecond) {
        const double* const s2 = p + kSecondState;
        e[q] = hn::MulAdd(hn::LowerHalf(hd, w1), hn::Load(hd, s2 + kPerNode),
                          hn::Mul(hn::LowerHalf(hd, w0), hn::Load(hd, s2)));
      }
    }
    const V a = hn::InterleaveLower(d, r[0], r[1]), b = hn::InterleaveUpper(d, r[0], r[1]),
            c = hn::InterleaveLower(d, r[2], r[3]), e4 = hn::InterleaveUpper(d, r[2], r[3]);
    h[0] = hn::ConcatLowerLower(d, c, a);
    h[1] = hn::ConcatLowerLower(d, e4, b);
    h[2] = hn::ConcatUpperUpper(d, c, a);
    h[3] = hn::ConcatUpperUpper(d, e4, b);
    if constexpr (kSecond) {
      const V ac = hn::Combine(d, e[2], e[0]), bd = hn::Combine(d, e[3], e[1]);
      h[4] = hn::InterleaveLower(d, ac, bd);
      h[5] = hn::InterleaveUpper(d, ac, bd);
    }
  }
};

// The lanes' strips: per lane q its strip (index, node 0, history, end), next node and running
// state (StripMarch's tx, ty, oldUpstream, sums) as rows of four, and the PackedStep constants of
// its two steps (entry: from the patch's leading edge to its first loaded node; full: between
// nodes) as rows of four. A lane not live repeats a live one (repeat): the same strip, node, state
// and constants, so it writes what that lane writes.
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
  using Constants = double[kConstants][kLanes];
  HWY_ALIGN Constants entry, full;
  HWY_ALIGN double v[kRunning][kLanes];
  const double* history[kLanes];  // Source::strip
  int strip[kLanes], first[kLanes], leave[kLanes], next[kLanes];
  bool live[kLanes];
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
// lateral coupling perTy[q]: PackedStep's arithmetic.
HWY_INLINE void pack(V H, V driveX, V perTy, const Pair& beta, double lagPerLength, double r,
                     double gy, double gphi, double a, Lanes::Constants& c) {
  using L = Lanes;
  const D d;
  const V one = hn::Set(d, 1.0), R = hn::Set(d, r);
  const V hbX = hn::Mul(H, hn::Set(d, beta(0))), hbY = hn::Mul(H, hn::Set(d, beta(1)));
  const V decayX = hn::Div(one, hn::Add(one, hbX)), decayY = hn::Div(one, hn::Add(one, hbY));
  hn::Store(hn::Mul(hn::Mul(hbX, R), decayX), d, c[L::kMemX]);
  hn::Store(hn::Mul(hn::Mul(hbY, R), decayY), d, c[L::kMemY]);
  hn::Store(hn::Mul(R, hn::Add(one, hbX)), d, c[L::kInverseX]);
  hn::Store(hn::Mul(R, hn::Add(one, hbY)), d, c[L::kInverseY]);
  hn::Store(hn::Set(d, r * r), d, c[L::kScale2]);
  const V lag = hn::Mul(H, hn::Set(d, lagPerLength));
  hn::Store(hn::Mul(lag, decayX), d, c[L::kLagX]);
  hn::Store(hn::Mul(lag, decayY), d, c[L::kLagY]);
  hn::Store(hn::Mul(hn::Mul(H, driveX), decayX), d, c[L::kPushX]);
  const V gphiV = hn::Set(d, gphi);
  const V pushY = hn::Mul(H, hn::MulAdd(hn::Mul(hn::Set(d, 0.5), H), gphiV, hn::Set(d, gy)));
  hn::Store(hn::Mul(pushY, decayY), d, c[L::kPushY]);
  hn::Store(decayX, d, c[L::kDecayX]);
  hn::Store(decayY, d, c[L::kDecayY]);
  hn::Store(hn::Mul(hn::Mul(hn::Mul(H, gphiV), hn::Set(d, a)), decayY), d, c[L::kPushPerXn]);
  hn::Store(hn::Mul(hn::Mul(hn::Mul(R, H), perTy), decayX), d, c[L::kCoupleX]);
}

// A group's start: lane q takes strip lanes->strip[q] of m's mesh, entering at its entry's h:
// both steps' constants (pack, on the strip's StripDrives), the running state zero.
template <class March>
void start(const March& m, Lanes* lanes) {
  double h[kLanes], step[kLanes], driveX[kLanes], perTy[kLanes];
  for (int q = 0; q < kLanes; ++q) {
    const int j = lanes->strip[q];
    const transient::StripDrives drives(m.mesh, j, m.gx, m.gphiX, m.coupling);
    h[q] = m.f->entry[j].h;
    step[q] = m.mesh.stripStep(j);
    driveX[q] = drives.x;
    perTy[q] = drives.perTy;
  }
  const V dx = load4(driveX), ty = load4(perTy);
  pack(load4(h), dx, ty, m.beta, m.X.lagPerLength, m.r, m.drive.gy, m.drive.gphi, m.a,
       lanes->entry);
  pack(load4(step), dx, ty, m.beta, m.X.lagPerLength, m.r, m.drive.gy, m.drive.gphi, m.a,
       lanes->full);
  for (auto& row : lanes->v) hn::Store(hn::Zero(D()), D(), row);
}

// Every lane not live repeats lane p: the same strip, node, state and constants (the full step's:
// a repeating lane is past its entry).
inline void repeat(int p, Lanes* lanes) {
  const D d;
  const bool* const live = lanes->live;
  HWY_ALIGN const int64_t deadLanes[kLanes] = {live[0] - 1, live[1] - 1, live[2] - 1, live[3] - 1};
  const M dead = hn::MaskFromVec(hn::BitCast(d, hn::Load(hn::RebindToSigned<D>(), deadLanes)));
  auto take = [&](double* row) {
    hn::Store(hn::IfThenElse(dead, hn::Set(d, row[p]), hn::Load(d, row)), d, row);
  };
  for (auto& row : lanes->full) take(row);
  for (auto& row : lanes->v) take(row);
  for (int q = 0; q < kLanes; ++q) {
    if (lanes->live[q]) continue;
    lanes->history[q] = lanes->history[p];
    lanes->strip[q] = lanes->strip[p];
    lanes->first[q] = lanes->first[p];
    lanes->leave[q] = lanes->leave[p];
    lanes->next[q] = lanes->next[p];
  }
}

// Nodes next[q] + i of the lanes' strips, i < n, on the step constants Lanes::full, the first on
// Lanes::entry where `entry` (the strips' first loaded nodes): StripMarch::step in every lane;
// reader.read(i, ...) gives their histories. Returns the number of nodes marched: n, or where
// a lane met the scalar reference's other paths (a tiny traction, a slip return out of range),
// which the caller takes one strip at a time; next advances by it.
template <bool kSecond, bool kResidualAlongTraction, class Reader>
HWY_NOINLINE int transientLanes(Lanes* lanes, bool entry, int n, const Reader& reader,
                                const double* xn, const FieldPointers& field,
                                const StateUpdate<kSecond>& update) {
  using L = Lanes;
  const D d;
  const FieldPointers out = field;
  double* const written = update.written;
  // The step's constants: the entry step's at the first node where `entry`, then the full step's.
  V memX, memY, lagX, lagY, pushX, pushY, decayX, decayY, pushPerXn, inverseX, inverseY, scale2,
      coupleX;
  auto steps = [&](const Lanes::Constants& c) HWY_ATTR {
    memX = hn::Load(d, c[L::kMemX]);
    memY = hn::Load(d, c[L::kMemY]);
    lagX = hn::Load(d, c[L::kLagX]);
    lagY = hn::Load(d, c[L::kLagY]);
    pushX = hn::Load(d, c[L::kPushX]);
    pushY = hn::Load(d, c[L::kPushY]);
    decayX = hn::Load(d, c[L::kDecayX]);
    decayY = hn::Load(d, c[L::kDecayY]);
    pushPerXn = hn::Load(d, c[L::kPushPerXn]);
    inverseX = hn::Load(d, c[L::kInverseX]);
    inverseY = hn::Load(d, c[L::kInverseY]);
    scale2 = hn::Load(d, c[L::kScale2]);
    coupleX = hn::Load(d, c[L::kCoupleX]);
  };
  steps(entry ? lanes->entry : lanes->full);
  const V rateX = hn::Set(d, update.rate(0)), rateY = hn::Set(d, update.rate(1)),
          rateOldX = hn::Set(d, update.rateOld(0)), rateOldY = hn::Set(d, update.rateOld(1)),
          poleOldX = hn::Set(d, update.poleOld(0)), poleOldY = hn::Set(d, update.poleOld(1));
  // SecondStateUpdate's constants (unused by the first-order march).
  V r2 = hn::Zero(d), rate2X = r2, rate2Y = r2, rate2OldX = r2, rate2OldY = r2, pole2OldX = r2,
    pole2OldY = r2;
  if constexpr (kSecond) {
    const auto& q = update.second;
    r2 = hn::Set(d, q.r);
    rate2X = hn::Set(d, q.rate2(0));
    rate2Y = hn::Set(d, q.rate2(1));
    rate2OldX = hn::Set(d, q.rate2Old(0));
    rate2OldY = hn::Set(d, q.rate2Old(1));
    pole2OldX = hn::Set(d, q.pole2Old(0));
    pole2OldY = hn::Set(d, q.pole2Old(1));
  }
  auto& v = lanes->v;
  V tx = hn::Load(d, v[L::kTx]), ty = hn::Load(d, v[L::kTy]), upX = hn::Load(d, v[L::kUpX]),
    upY = hn::Load(d, v[L::kUpY]), sumX = hn::Load(d, v[L::kSumX]), sumY = hn::Load(d, v[L::kSumY]),
    sumXnY = hn::Load(d, v[L::kSumXnY]), loaded = hn::Load(d, v[L::kLoaded]),
    stuck = hn::Load(d, v[L::kStuck]);
  const V one = hn::Set(d, 1.0), zero = hn::Zero(d);
  const int* const next = lanes->next;
  const int k0[kLanes] = {next[0], next[1], next[2], next[3]};
  int i = 0;
  for (; i < n; ++i) {
    const int node[kLanes] = {k0[0] + i, k0[1] + i, k0[2] + i, k0[3] + i};
    // Node k's history is written at written + kPerNode k; in place it is read there too.
    double* const p[kLanes] = {written + kPerNode * node[0], written + kPerNode * node[1],
                               written + kPerNode * node[2], written + kPerNode * node[3]};
    V h[6];  // oldX, oldY, sX, sY, s2X, s2Y
    reader.template read<kSecond>(i, p, h);
    const V oldX = h[0], oldY = h[1], sX = h[2], sY = h[3];
    // PackedStep's history, memory tau_old - lag s_old - push, and the coupling's part.
    V guessX = hn::Sub(hn::NegMulAdd(lagX, sX, hn::Mul(memX, oldX)), pushX);
    if constexpr (kResidualAlongTraction) guessX = hn::NegMulAdd(coupleX, upY, guessX);
    const V guessY = hn::Sub(hn::NegMulAdd(lagY, sY, hn::Mul(memY, oldY)), pushY);
    const V x = at(xn, node), ownY = hn::NegMulAdd(pushPerXn, x, guessY);
    // The upstream traction enters last: it is the only operand on the march's serial chain.
    const V nx = hn::MulAdd(decayX, tx, guessX), ny = hn::MulAdd(decayY, ty, ownY);
    const V g = at(out.bound, node), g2 = hn::Mul(g, g);
    const V t2 = hn::MulAdd(nx, nx, hn::Mul(ny, ny));
    const M slips = hn::Gt(t2, g2);
    M stop = outsideLanes(t2, g2);  // StripSums::node's tiny path: the lanes stop
    if (!any(slips)) {
      // All four in adhesion: the traction is the guess. A branch, not a select: the slip
      // return's square root and division would otherwise sit on the running traction's chain.
      if (any(stop)) break;
      tx = nx;
      ty = ny;
    } else if constexpr (kResidualAlongTraction) {
      // transient::slipsAlongTheResidual in every lane, taken where the lane slips.
      const V rX = hn::MulAdd(hn::NegMulAdd(memX, oldX, guessX), inverseX, hn::Mul(scale2, upX));
      const V rY = hn::MulAdd(hn::NegMulAdd(memY, oldY, ownY), inverseY, hn::Mul(scale2, upY));
      const V excess = hn::Max(zero, hn::Sub(hn::MulAdd(rX, oldX, hn::Mul(rY, oldY)), g2));
      const V dX = hn::Mul(nx, hn::MulAdd(excess, decayY, g2));
      const V dY = hn::Mul(ny, hn::MulAdd(excess, decayX, g2));
      const V d2 = hn::MulAdd(dX, dX, hn::Mul(dY, dY));
      const M inRange = hn::And(hn::Gt(d2, hn::Set(d, 1e-300)), hn::Lt(d2, hn::Set(d, 1e300)));
      stop = hn::Or(stop, hn::AndNot(inRange, slips));
      if (any(stop)) break;
      const V scale = hn::Div(g, hn::Sqrt(d2));
      tx = hn::IfThenElse(slips, hn::Mul(dX, scale), nx);
      ty = hn::IfThenElse(slips, hn::Mul(dY, scale), ny);
    } else {
      // StripSums::node: the guess scaled onto the bound.
      if (any(stop)) break;
      const V scale = hn::Div(g, hn::Sqrt(t2));
      tx = hn::IfThenElse(slips, hn::Mul(nx, scale), nx);
      ty = hn::IfThenElse(slips, hn::Mul(ny, scale), ny);
    }
    if constexpr (kResidualAlongTraction) {
      upX = oldX;
      upY = oldY;
    }
    // StripSums::add.
    scatter(tx, out.tx, node);
    scatter(ty, out.ty, node);
    storeFlags(slips, out.slip, node);
    sumX = hn::Add(sumX, tx);
    sumY = hn::Add(sumY, ty);
    sumXnY = hn::MulAdd(x, ty, sumXnY);
    const M pressed = hn::Gt(g, zero);
    loaded = hn::Add(loaded, hn::IfThenElseZero(pressed, one));
    stuck = hn::Add(stuck, hn::IfThenElseZero(hn::AndNot(slips, pressed), one));
    // StateUpdate: rate tau - rateOld tau_old - poleOld s (+ r s2).
    V nextX = hn::NegMulAdd(poleOldX, sX, hn::NegMulAdd(rateOldX, oldX, hn::Mul(rateX, tx)));
    V nextY = hn::NegMulAdd(poleOldY, sY, hn::NegMulAdd(rateOldY, oldY, hn::Mul(rateY, ty)));
    if constexpr (kSecond) {
      const V s2X = h[4], s2Y = h[5];
      nextX = hn::MulAdd(r2, s2X, nextX);
      nextY = hn::MulAdd(r2, s2Y, nextY);
      join(hn::NegMulAdd(pole2OldX, sX, hn::NegMulAdd(rate2OldX, oldX, hn::Mul(rate2X, tx))),
           hn::NegMulAdd(pole2OldY, sY, hn::NegMulAdd(rate2OldY, oldY, hn::Mul(rate2Y, ty))), p,
           kSecondState);
    }
    join(nextX, nextY, p, kState);
    join(tx, ty, p, kTraction);
    if (i == 0 && entry) steps(lanes->full);
  }
  const V rows[L::kRunning] = {tx, ty, upX, upY, sumX, sumY, sumXnY, loaded, stuck};
  for (int r = 0; r < L::kRunning; ++r) hn::Store(rows[r], d, v[r]);
  for (int q = 0; q < kLanes; ++q) lanes->next[q] += i;
  return i;
}

// The time-term march in lanes, four strips at a time. The strips go in groups of four in
// centre-out order: on a fixed mesh a strip's loaded length falls with |y|, so a group's strips
// are about as long, and on the adaptive mesh all are. A group's constants are set up in the lanes
// (start), its first loaded nodes marched in them; a lane whose strip ends repeats one that still
// marches. A strip left over alone at the edges goes one strip at a time, as do the nodes where
// the lanes stop. The strips' sums are added in strip order at the end.
template <bool kSecond, bool kResidualAlongTraction, class Source>
CreepForces transientInLanes(const transient::TransientStep& step, const Source& source) {
  using March = transient::TransientMarch<kSecond, kResidualAlongTraction, Source>;
  using Strip = typename March::Strip;
  const March m(step, source);
  m.outside();
  const auto update = m.update;
  const Source history = m.history;
  const FieldPointers out = m.out;
  const double* const xn = m.xn;
  const int nx = m.nx, ny = m.ny;
  const PatchMesh& mesh = m.mesh;
  TractionField* const f = step.f;
  auto marchOne = [&](int j) {
    Strip A = m.strip(j);
    if (A.enter < A.leave) A.node(A.enter, A.entry, history, xn, out, update);
    for (int k = A.enter + 1; k < A.leave; ++k) A.node(k, A.full, history, xn, out, update);
    return A.sums;
  };
  StripSums* const stripSums = TransientStorage::stripSums(ny, step.st);
  Lanes lanes;
  // n nodes of every lane, the first on the strips' entry steps where entryFirst, the nodes the
  // lanes stop at one strip at a time; own: a live lane.
  auto marchLanes = [&](bool entryFirst, int n, int own) {
    int done = 0;
    while (done < n) {
      const bool entry = entryFirst && done == 0;
      const int left = n - done;
      if constexpr (Source::kMapped) {
        int from[kLanes];
        for (int q = 0; q < kLanes; ++q) from[q] = lanes.next[q] - lanes.first[q];
        bool aligned = true;  // the four march the same nodes of their strips
        for (int q = 1; q < kLanes; ++q) aligned = aligned && from[q] == from[0];
        const double* const strips[kLanes] = {lanes.history[0], lanes.history[1], lanes.history[2],
                                              lanes.history[3]};
        if (aligned) {
          const CarriedReader<true> reader{history.offsets,
                                           history.weights,
                                           {strips[0], strips[1], strips[2], strips[3]},
                                           {from[0], from[1], from[2], from[3]}};
          done += transientLanes<kSecond, kResidualAlongTraction>(&lanes, entry, left, reader, xn,
                                                                  out, update);
        } else {
          const CarriedReader<false> reader{history.offsets,
                                            history.weights,
                                            {strips[0], strips[1], strips[2], strips[3]},
                                            {from[0], from[1], from[2], from[3]}};
          done += transientLanes<kSecond, kResidualAlongTraction>(&lanes, entry, left, reader, xn,
                                                                  out, update);
        }
      } else {
        done += transientLanes<kSecond, kResidualAlongTraction>(&lanes, entry, left,
                                                                InPlaceReader{}, xn, out, update);
      }
      if (done == n) break;
      // The node the lanes stopped at, one strip at a time.
      for (int q = 0; q < kLanes; ++q) {
        if (!lanes.live[q]) continue;
        Strip s = m.strip(lanes.strip[q]);
        lanes.give(q, &s);
        s.node(lanes.next[q], entry ? s.entry : s.full, history, xn, out, update);
        lanes.take(q, s);
        ++lanes.next[q];
      }
      repeat(own, &lanes);
      ++done;
    }
  };
  for (int k = 0; k < ny;) {
    int count = 0;
    for (; k < ny && count < kLanes; ++k) {
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
      lanes.live[count] = true;
      ++count;
    }
    if (count == 0) break;
    // A last, outermost strip alone goes one strip at a time: a node-row of the lanes costs about
    // what it costs with four live lanes.
    if (count == 1) {
      stripSums[lanes.strip[0]] = marchOne(lanes.strip[0]);
      break;
    }
    for (int q = count; q < kLanes; ++q) {  // the group's last lanes repeat its last strip
      lanes.strip[q] = lanes.strip[count - 1];
      lanes.first[q] = lanes.first[count - 1];
      lanes.next[q] = lanes.next[count - 1];
      lanes.leave[q] = lanes.leave[count - 1];
      lanes.history[q] = lanes.history[count - 1];
      lanes.live[q] = false;
    }
    start(m, &lanes);
    // The first loaded node steps from the patch's leading edge, where the traction is zero.
    for (bool entry = true;; entry = false) {
      int n = std::numeric_limits<int>::max(), own = -1;
      bool ended = false;  // a lane's strip ended: the lanes repeating it must move on
      for (int q = 0; q < kLanes; ++q) {
        if (!lanes.live[q]) continue;
        if (lanes.next[q] == lanes.leave[q]) {
          stripSums[lanes.strip[q]] = lanes.sums(q);
          lanes.live[q] = false;
          ended = true;
        } else {
          n = std::min(n, lanes.leave[q] - lanes.next[q]);
          own = q;
        }
      }
      if (own < 0) break;
      if (ended) repeat(own, &lanes);
      marchLanes(entry, n, own);
    }
  }
  ForceSums sums;
  for (int j = 0; j < ny; ++j) sums.addStrip(mesh, j, stripSums[j], f->entry[j], out.tx, out.ty);
  return sums.forces();
}

template <class Source>
CreepForces transientInLanes(const transient::TransientStep& step, const Source& source) {
  const bool residual = step.st->saturation() == TransientState::Saturation::kResidualAlongTraction;
  if (step.second)
    return residual ? transientInLanes<true, true>(step, source)
                    : transientInLanes<true, false>(step, source);
  return residual ? transientInLanes<false, true>(step, source)
                  : transientInLanes<false, false>(step, source);
}

CreepForces TransientLanes(const transient::TransientStep& step) {
  if (step.map) return transientInLanes(step, transient::CarriedHistory(*step.map, *step.previous));
  return transientInLanes(step, transient::InPlace{});
}

bool HasLanes() {
  return true;
}

#else  // no lanes on this target: the scalar reference marches (stripLanesAvailable is false)

CreepForces SteadyLanes(const PatchMesh&, const Flexibilities&, const Creepages&, TractionField*) {
  return {};
}
CreepForces TransientLanes(const transient::TransientStep&) {
  return {};
}
bool HasLanes() {
  return false;
}

#endif

}  // namespace HWY_NAMESPACE
}  // namespace wheel_rail_contact
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wheel_rail_contact {

HWY_EXPORT(SteadyLanes);
HWY_EXPORT(TransientLanes);
HWY_EXPORT(HasLanes);

bool stripLanesAvailable() {
  static const bool available = HWY_DYNAMIC_DISPATCH(HasLanes)();  // asked once
  return available;
}

CreepForces steadyFastSimInLanes(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                                 TractionField* field) {
  return HWY_DYNAMIC_DISPATCH(SteadyLanes)(mesh, L, c, field);
}

CreepForces transientFastSimInLanes(const transient::TransientStep& step) {
  return HWY_DYNAMIC_DISPATCH(TransientLanes)(step);
}

}  // namespace wheel_rail_contact
#endif
