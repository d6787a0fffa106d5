/// Four doubles in the lanes of an AVX register, for the calibration's own vectorised step
/// (calibration_table.cpp, correctedExps) until it moves to Highway as the marches have
/// (strip_lanes.hpp). The operations are AVX's plain ones, never fused multiply-adds, so a lane's
/// result is that of the scalar path bit for bit. Compiled for AVX function by function and called
/// only where the CPU has it (fourStripLanesAvailable, fastsim.hpp); WRC_FOUR_STRIP_LANES is
/// defined where they exist at all (x86-64 with GCC or clang).
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define WRC_FOUR_STRIP_LANES 1
#include <immintrin.h>

namespace wheel_rail_contact {
namespace avx {

#define WRC_AVX_INLINE [[gnu::target("avx"), gnu::always_inline]] inline
using V = __m256d;
WRC_AVX_INLINE V load(const double* p) {  // 32-byte aligned
  return _mm256_load_pd(p);
}
WRC_AVX_INLINE void store(double* p, V v) {  // 32-byte aligned
  _mm256_store_pd(p, v);
}
WRC_AVX_INLINE V add(V a, V b) {
  return _mm256_add_pd(a, b);
}
WRC_AVX_INLINE V sub(V a, V b) {
  return _mm256_sub_pd(a, b);
}
WRC_AVX_INLINE V mul(V a, V b) {
  return _mm256_mul_pd(a, b);
}

}  // namespace avx
}  // namespace wheel_rail_contact
#endif
