/// Four doubles in the lanes of an AVX register, for the marches that take four strips at a time
/// (one strip a lane: fastsim.cpp's coupled steady march, transient_fastsim.cpp's calibrated
/// march). The operations are AVX's plain ones, never fused multiply-adds, so a lane's result is
/// that of the scalar march bit for bit. Compiled for AVX function by function and called only
/// where the CPU has it (fourStripLanesAvailable, fastsim.hpp); WRC_FOUR_STRIP_LANES is defined
/// where they exist at all (x86-64 with GCC or clang).
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define WRC_FOUR_STRIP_LANES 1
#include <immintrin.h>

#include <cstdint>
#include <cstring>

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
/// v[k[q]] in lane q.
WRC_AVX_INLINE V at(const double* v, const int* k) {
  return _mm256_set_pd(v[k[3]], v[k[2]], v[k[1]], v[k[0]]);
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
WRC_AVX_INLINE V greater(V a, V b) {  // a > b
  return _mm256_cmp_pd(a, b, _CMP_GT_OQ);
}
/// mask ? yes : no per lane, mask all ones or all zeros (a comparison's). Not blendv: GCC turns
/// blendv on a comparison's mask into four scalar branches.
WRC_AVX_INLINE V select(V mask, V yes, V no) {
  return _mm256_or_pd(_mm256_and_pd(mask, yes), _mm256_andnot_pd(mask, no));
}
/// v's first kLive lanes into v0[k[q]].
template <int kLive = 4>
WRC_AVX_INLINE void scatter(V v, double* v0, const int* k) {
  const __m128d lo = _mm256_castpd256_pd128(v);
  _mm_storel_pd(v0 + k[0], lo);
  if constexpr (kLive > 1) _mm_storeh_pd(v0 + k[1], lo);
  if constexpr (kLive > 2) {
    const __m128d hi = _mm256_extractf128_pd(v, 1);
    _mm_storel_pd(v0 + k[2], hi);
    if constexpr (kLive > 3) _mm_storeh_pd(v0 + k[3], hi);
  }
}
/// Where StripSums::node's tiny path (|t|^2 = t2 not above 1e-300, or NaN: |t| measured by hypot)
/// could differ from the lanes' t2 > g^2: a tiny or NaN t2 next to a bound not far above it. Where
/// the bound is far above (g2 > 1e-290) the tiny path keeps the traction, as the lanes do.
WRC_AVX_INLINE V outsideLanes(V t2, V g2) {
  const V tiny = _mm256_cmp_pd(t2, _mm256_set1_pd(1e-300), _CMP_NGT_UQ);
  const V keeps = _mm256_and_pd(_mm256_cmp_pd(t2, _mm256_set1_pd(1e-300), _CMP_LE_OQ),
                                greater(g2, _mm256_set1_pd(1e-290)));
  return _mm256_andnot_pd(keeps, tiny);
}
// Byte q of kSlipBytes[m] is bit q of m: four slip flags from one comparison's mask.
constexpr std::uint32_t kSlipBytes[16] = {
    0x00000000, 0x00000001, 0x00000100, 0x00000101, 0x00010000, 0x00010001, 0x00010100, 0x00010101,
    0x01000000, 0x01000001, 0x01000100, 0x01000101, 0x01010000, 0x01010001, 0x01010100, 0x01010101};
/// The first kLive of four slip flags, lane q's into flags[k[q]], from a comparison's mask's bits
/// (movemask).
template <int kLive = 4>
WRC_AVX_INLINE void storeFlags(int bits, bool* flags, const int* k) {
  const std::uint32_t bytes = kSlipBytes[bits];
  for (int q = 0; q < kLive; ++q) {
    const auto flag = static_cast<std::uint8_t>(bytes >> (8 * q));
    std::memcpy(flags + k[q], &flag, 1);  // a bool's byte, 0 or 1
  }
}

}  // namespace avx
}  // namespace wheel_rail_contact
#endif
