// The calibrated step's vector path (correction_lanes.hpp) in Highway's portable vector
// operations, compiled and dispatched as the marches' (strip_lanes.cpp): once per Highway target,
// the baseline (no lanes) and AVX2 (four doubles a register), the best one this CPU has picked
// once at run time (HWY_DYNAMIC_DISPATCH).
#include "core/calibration/correction_lanes.hpp"

#include <cmath>
#include <cstddef>

#include "core/calibration/calibration_schema.hpp"

#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS (HWY_SSSE3 | HWY_SSE4 | HWY_AVX3 | HWY_AVX3_DL)
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/calibration/correction_lanes.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

#include <hwy/contrib/math/math-inl.h>

HWY_BEFORE_NAMESPACE();
namespace wheel_rail_contact {
namespace calibration {
namespace HWY_NAMESPACE {

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::FixedTag<double, 4>;  // a multiplier a lane
using V = hn::Vec<D>;

// Highway's Exp is valid up to +706 and its scaling leaves the normal range below about -708:
// outside |x| < 700, and for NaN, std::exp lane by lane.
HWY_INLINE void exps(V x, double* r) {
  const D d;
  hn::StoreU(hn::Exp(d, x), d, r);
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
