// Single-precision lanes for the shading kernels (hit_shading.cpp, reflection_frame.cpp):
// four (SSE2) wherever x86-64 is, eight (AVX) where the CPU has it, chosen at run time by
// has_avx(). Each operation is one IEEE single operation per lane and none is fused, so a
// kernel that keeps the scalar code's order gives its bits in every lane.
#pragma once

#include <cstddef>
#if defined(__SSE2__)
#include <emmintrin.h>
#define PROXIMA_SHADE_LANES 1
#else
#define PROXIMA_SHADE_LANES 0
#endif
// The eight-lane path: GCC optimized builds only, as the best match's AVX-512 path
// (temporal_best_match.cpp) — unoptimized, the lane ops would not be inlined into the avx
// code and would pass __m256 across targets; clang rejects the default-target template.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__OPTIMIZE__)
#include <immintrin.h>
#define PROXIMA_SHADE_AVX 1
#pragma GCC diagnostic ignored "-Wpsabi"
#else
#define PROXIMA_SHADE_AVX 0
#endif

namespace proxima {

#if PROXIMA_SHADE_LANES
#define PROXIMA_LANE_OP static inline __attribute__((always_inline))
struct Lanes4 {
  using V = __m128;
  static constexpr size_t kWidth = 4;
  PROXIMA_LANE_OP V zero() { return _mm_setzero_ps(); }
  PROXIMA_LANE_OP V set1(float v) { return _mm_set1_ps(v); }
  PROXIMA_LANE_OP V load(const float* p) { return _mm_loadu_ps(p); }
  PROXIMA_LANE_OP void store(float* p, V v) { _mm_storeu_ps(p, v); }
  PROXIMA_LANE_OP V add(V a, V b) { return _mm_add_ps(a, b); }
  PROXIMA_LANE_OP V sub(V a, V b) { return _mm_sub_ps(a, b); }
  PROXIMA_LANE_OP V mul(V a, V b) { return _mm_mul_ps(a, b); }
  PROXIMA_LANE_OP V div(V a, V b) { return _mm_div_ps(a, b); }
  PROXIMA_LANE_OP V sqrt(V a) { return _mm_sqrt_ps(a); }
  PROXIMA_LANE_OP V neg(V a) { return _mm_xor_ps(a, _mm_set1_ps(-0.0f)); }
  PROXIMA_LANE_OP V keep(V mask, V a) { return _mm_and_ps(mask, a); }
  PROXIMA_LANE_OP V both(V a, V b) { return _mm_and_ps(a, b); }
  PROXIMA_LANE_OP V gt0(V a) { return _mm_cmplt_ps(_mm_setzero_ps(), a); }     // 0 < a (NaN: false)
  PROXIMA_LANE_OP V dot(V ax, V ay, V az, V bx, V by, V bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }
  PROXIMA_LANE_OP V not_le0(V a) { return _mm_cmpnle_ps(a, _mm_setzero_ps()); }  // !(a <= 0) (NaN: true)
};
#endif

#if PROXIMA_SHADE_AVX
// Eight lanes where the CPU has AVX (runtime dispatch). target("avx") brings no fused
// multiply-add, so the operations stay separate: the same bits as four lanes.
#define PROXIMA_AVX_OP static __attribute__((target("avx"))) inline
struct Lanes8 {
  using V = __m256;
  static constexpr size_t kWidth = 8;
  PROXIMA_AVX_OP V zero() { return _mm256_setzero_ps(); }
  PROXIMA_AVX_OP V set1(float v) { return _mm256_set1_ps(v); }
  PROXIMA_AVX_OP V load(const float* p) { return _mm256_loadu_ps(p); }
  PROXIMA_AVX_OP void store(float* p, V v) { _mm256_storeu_ps(p, v); }
  PROXIMA_AVX_OP V add(V a, V b) { return _mm256_add_ps(a, b); }
  PROXIMA_AVX_OP V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  PROXIMA_AVX_OP V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  PROXIMA_AVX_OP V div(V a, V b) { return _mm256_div_ps(a, b); }
  PROXIMA_AVX_OP V sqrt(V a) { return _mm256_sqrt_ps(a); }
  PROXIMA_AVX_OP V neg(V a) { return _mm256_xor_ps(a, _mm256_set1_ps(-0.0f)); }
  PROXIMA_AVX_OP V keep(V mask, V a) { return _mm256_and_ps(mask, a); }
  PROXIMA_AVX_OP V both(V a, V b) { return _mm256_and_ps(a, b); }
  PROXIMA_AVX_OP V gt0(V a) { return _mm256_cmp_ps(_mm256_setzero_ps(), a, _CMP_LT_OS); }
  PROXIMA_AVX_OP V dot(V ax, V ay, V az, V bx, V by, V bz) { return add(add(mul(ax, bx), mul(ay, by)), mul(az, bz)); }
  PROXIMA_AVX_OP V not_le0(V a) { return _mm256_cmp_ps(a, _mm256_setzero_ps(), _CMP_NLE_US); }
};

inline bool has_avx() {
  static const bool yes = __builtin_cpu_supports("avx");
  return yes;
}
#endif

}  // namespace proxima
