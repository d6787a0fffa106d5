// The calibrated step's vector path (correction_lanes.hpp) in Highway's portable vector
// operations, compiled and dispatched as the marches' (strip_lanes.cpp): once per Highway target,
// the baseline (no lanes) and AVX2 (four doubles a register), the best one this CPU has picked
// once at run time (HWY_DYNAMIC_DISPATCH).
#include "core/calibration/correction_lanes.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "core/calibration/calibration_schema.hpp"

#ifndef WHEEL_RAIL_CONTACT_CORRECTION_LANES_EXP_TABLE
#define WHEEL_RAIL_CONTACT_CORRECTION_LANES_EXP_TABLE
namespace wheel_rail_contact {
namespace calibration {
namespace {
// The lanes' exp (exps below): with x = (m + i / 128) ln 2 + r, |r| <= ln 2 / 256,
// exp(x) = 2^m 2^(i / 128) exp(r), 2^(i / 128) from this table and exp(r) - 1 from its Taylor
// polynomial to r^5 (truncation below 1e-18 relative): within an ulp of the exact value, with no
// special cases inside |x| < 700. (The scheme is glibc's exp with a table of 128; it costs the step
// less than Highway's Exp, whose polynomial is longer: doc/performance.md.)
struct Exp2Table {
  // bits of 2^(i / 128) less i << 45: adding k << 45 (k = 128 m + i) then gives 2^m 2^(i / 128).
  std::uint64_t bits[128];
  Exp2Table() {
    for (int i = 0; i < 128; ++i) {
      const double v = std::exp2(i / 128.0);
      std::memcpy(&bits[i], &v, sizeof v);
      bits[i] -= static_cast<std::uint64_t>(i) << 45;
    }
  }
};
const Exp2Table kExp2Table;
constexpr double kExpPerLn2 = 128.0 / M_LN2, kExpShift = 0x1.8p52;
constexpr double kExpLn2Hi = 0x1.62e42fefa0000p-8, kExpLn2Lo = 0x1.cf79abc9e3b3ap-47;  // ln 2 / 128
}  // namespace
}  // namespace calibration
}  // namespace wheel_rail_contact
#endif

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4 | HWY_AVX3 | HWY_AVX3_DL)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/calibration/correction_lanes.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wheel_rail_contact {
namespace calibration {
namespace HWY_NAMESPACE {

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::FixedTag<double, 4>;  // a multiplier a lane
using V = hn::Vec<D>;

// The table exp (Exp2Table above). Outside |x| < 700, where 2^m leaves the normal range, and for
// NaN, std::exp lane by lane.
HWY_INLINE void exps(V x, double* r) {
  const D d;
  const hn::RebindToUnsigned<D> du;
  const hn::RebindToSigned<D> di;
  // k = round(x 128 / ln 2) in the low bits of kd (the shift's mantissa holds it).
  const V shift = hn::Set(d, kExpShift);
  const V kd0 = hn::MulAdd(x, hn::Set(d, kExpPerLn2), shift);
  const auto ki = hn::BitCast(du, kd0);
  const V kd = hn::Sub(kd0, shift);
  const V q = hn::NegMulAdd(kd, hn::Set(d, kExpLn2Lo), hn::NegMulAdd(kd, hn::Set(d, kExpLn2Hi), x));
  const V q2 = hn::Mul(q, q);
  const V p =
      hn::MulAdd(hn::Mul(q2, q2), hn::MulAdd(q, hn::Set(d, 1.0 / 120.0), hn::Set(d, 1.0 / 24.0)),
                 hn::MulAdd(q2, hn::MulAdd(q, hn::Set(d, 1.0 / 6.0), hn::Set(d, 0.5)), q));
  // 2^m 2^(i / 128) for k = 128 m + i in ki's low bits.
  const auto index = hn::BitCast(di, hn::And(ki, hn::Set(du, 127)));
  const auto bits = hn::GatherIndex(du, kExp2Table.bits, index);
  const V scale = hn::BitCast(d, hn::Add(bits, hn::ShiftLeft<45>(ki)));
  hn::StoreU(hn::MulAdd(scale, p, scale), d, r);
  const auto inRange = hn::Lt(hn::Abs(x), hn::Set(d, 700.0));  // false for NaN
  if (!hn::AllTrue(d, inRange)) {
    HWY_ALIGN double xs[4];
    hn::Store(x, d, xs);
    for (int q = 0; q < 4; ++q)
      if (!(std::fabs(xs[q]) < 700.0)) r[q] = std::exp(xs[q]);
  }
}

void Exps(const double* x, double* r) {
  exps(hn::LoadU(D(), x), r);
}

void CorrectedExps(const double* lo, std::size_t alongT, std::size_t alongS, std::size_t branch,
                   double we, double wt, double ws, double opposed, const double* base, double* r) {
  constexpr std::size_t P = kMultipliers;  // a grid point's multipliers lie side by side
  const D d;
  const V weV = hn::Set(d, we), wtV = hn::Set(d, wt), restT = hn::Set(d, 1.0 - wt),
          wsV = hn::Set(d, ws), restS = hn::Set(d, 1.0 - ws);
  // Along e from a corner's knot k - 1 to k, then along xi's share, then spin's.
  auto along = [&](const double* x) HWY_ATTR {
    const V x0 = hn::LoadU(d, x);
    return hn::MulAdd(weV, hn::Sub(hn::LoadU(d, x + P), x0), x0);
  };
  auto inCell = [&](const double* l0) HWY_ATTR {
    const double* h0 = l0 + alongS;
    const V l = hn::MulAdd(restT, along(l0), hn::Mul(wtV, along(l0 + alongT)));
    const V h = hn::MulAdd(restT, along(h0), hn::Mul(wtV, along(h0 + alongT)));
    return hn::MulAdd(restS, l, hn::Mul(wsV, h));
  };
  V lm;
  if (opposed <= 0.0)
    lm = inCell(lo);
  else if (opposed >= 1.0)
    lm = inCell(lo + branch);
  else
    lm = hn::MulAdd(hn::Set(d, 1.0 - opposed), inCell(lo),
                    hn::Mul(hn::Set(d, opposed), inCell(lo + branch)));
  exps(hn::Add(hn::LoadU(d, base), lm), r);
}

#else  // no lanes on this target: step() takes the scalar reference (stripLanesAvailable false)

void Exps(const double* x, double* r) {
  for (int q = 0; q < 4; ++q) r[q] = std::exp(x[q]);
}
void CorrectedExps(const double*, std::size_t, std::size_t, std::size_t, double, double, double,
                   double, const double*, double*) {}

#endif

}  // namespace HWY_NAMESPACE
}  // namespace calibration
}  // namespace wheel_rail_contact
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wheel_rail_contact {
namespace calibration {

HWY_EXPORT(Exps);
HWY_EXPORT(CorrectedExps);

void expsInLanes(const double* x, double* r) {
  HWY_DYNAMIC_DISPATCH(Exps)(x, r);
}

void correctedExpsInLanes(const double* lo, std::size_t alongT, std::size_t alongS,
                          std::size_t branch, double we, double wt, double ws, double opposed,
                          const double* base, double* r) {
  HWY_DYNAMIC_DISPATCH(CorrectedExps)(lo, alongT, alongS, branch, we, wt, ws, opposed, base, r);
}

}  // namespace calibration
}  // namespace wheel_rail_contact
#endif
