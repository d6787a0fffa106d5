/// The calibrated step's vector path (PatchCalibration::step where vectorised()): the combined
/// correction's interpolation for the first four multipliers and their four exps, one multiplier
/// in each lane of a vector register.
///
///   Lanes: 4 doubles (Highway, compiled for x86's AVX2 and chosen at run time as the marches'
///          strip_lanes.hpp; elsewhere stripLanesAvailable() is false and the scalar reference
///          runs).
///   Error: within 1e-12 relative of the scalar reference: the lanes fuse multiply-adds, and
///          their exp is a table exp in Highway's operations (correction_lanes.cpp, within 1 ulp)
///          where the reference calls std::exp.
///   Range: every input. A lane whose exp argument is outside |x| < 700 (where the table exp's
///          2^m leaves the normal range), or NaN, takes std::exp.
#pragma once

#include <cstddef>

namespace wheel_rail_contact {
namespace calibration {

/// exp(x[q]) into r[q] for q = 0..3 (with the range's fallback above).
void expsInLanes(const double* x, double* r);

/// The correction's cell (PatchCalibration::CorrectionCell: first corner `lo`, the strides to the
/// next xi share, spin share and branch, the weights along e, xi's share and spin's share) at
/// branch weight `opposed`: multiplier q's ln m_q (q = 0..3, the four contiguous at each corner),
/// into r[q] exp(base[q] + ln m_q).
void correctedExpsInLanes(const double* lo, std::size_t alongT, std::size_t alongS,
                          std::size_t branch, double we, double wt, double ws, double opposed,
                          const double* base, double* r);

}  // namespace calibration
}  // namespace wheel_rail_contact
