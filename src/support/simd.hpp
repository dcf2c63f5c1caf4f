#pragma once
// The library's fixed-width vector layer (internal; public headers never include it), one of the two files of the
// instruction-set seam (the other, simd_versions.hpp, compiles a kernel once per level and dispatches to it). Only
// these two files and simd_level.cpp name instruction sets or target options.
//
// Types are the compiler's vector extension (GCC and Clang, any architecture): four or eight float or 32-bit integer
// lanes, two or four double or 64-bit integer lanes. Arithmetic and comparisons are the built-in operators (a
// comparison gives an integer vector of lane masks, all ones or zero; the library is built without contraction, so
// products are never fused and a kernel gives the same bits at every width). Each level's lane set names its types and
// adds what the operators do not say: unaligned and partial loads and stores, broadcasts, the minimum and maximum of
// SSE (the second operand where either is NaN), selects, square roots, transposes, lane masks as bits, dropping the
// bits past a range's end, and widening a row of lane numbers to positions:
//   baseline_lanes  four floats or ints, two doubles (SSE2 on x86-64, NEON on ARM, scalar code elsewhere);
//   avx2_lanes      eight floats or ints, four doubles (x86-64 only; its operations run only inside a kernel version
//                   compiled for AVX2 or AVX-512, see simd_versions.hpp).
// Kernels written lane by lane for the compiler to vectorize use LaneArray and LaneVector3 (plain arrays of lanes).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "support/simd_level.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// Defined where the AVX2 and AVX-512 versions of the kernels are compiled in (x86-64 with GCC or Clang).
#define CLOTHCD_SIMD_X86 1
#include <immintrin.h>
/// Marks one function of avx2_lanes compiled for AVX2 and BMI2 (inlined only into kernel versions for AVX2 or up).
#define CLOTHCD_SIMD_AVX2 __attribute__((target("avx2,bmi2")))
#if defined(__clang__)
#define CLOTHCD_SIMD_BEGIN_AVX2 \
  _Pragma("clang attribute push(__attribute__((target(\"avx2,bmi2\"))), apply_to = function)")
#define CLOTHCD_SIMD_BEGIN_AVX512 \
  _Pragma("clang attribute push(__attribute__((target(\"avx2,bmi2,avx512f\"))), apply_to = function)")
#define CLOTHCD_SIMD_END _Pragma("clang attribute pop")
#else
/// Every function defined from here to CLOTHCD_SIMD_END is compiled for AVX2 and BMI2.
#define CLOTHCD_SIMD_BEGIN_AVX2 _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,bmi2\")")
/// Every function defined from here to CLOTHCD_SIMD_END is compiled for AVX-512F (with AVX2 and BMI2).
#define CLOTHCD_SIMD_BEGIN_AVX512 _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,bmi2,avx512f\")")
/// Ends CLOTHCD_SIMD_BEGIN_AVX2 or CLOTHCD_SIMD_BEGIN_AVX512.
#define CLOTHCD_SIMD_END _Pragma("GCC pop_options")
#endif
#endif

namespace clothcd::simd {

/// Four float lanes.
using F32x4 = float __attribute__((vector_size(16)));
/// Four 32-bit integer lanes (also the lane masks of F32x4 comparisons).
using I32x4 = std::int32_t __attribute__((vector_size(16)));
/// Eight float lanes (AVX).
using F32x8 = float __attribute__((vector_size(32)));
/// Eight 32-bit integer lanes (also the lane masks of F32x8 comparisons; AVX).
using I32x8 = std::int32_t __attribute__((vector_size(32)));
/// Two double lanes (the baseline: SSE2 on x86-64, NEON on ARM, scalar code elsewhere).
using F64x2 = double __attribute__((vector_size(16)));
/// Two 64-bit integer lanes (the lane masks of F64x2 comparisons).
using I64x2 = std::int64_t __attribute__((vector_size(16)));
/// Four double lanes (AVX).
using F64x4 = double __attribute__((vector_size(32)));
/// Four 64-bit integer lanes (the lane masks of F64x4 comparisons; AVX).
using I64x4 = std::int64_t __attribute__((vector_size(32)));

// ---- the baseline's lanes: two doubles (interval arithmetic keeps an interval's two bounds in one vector), four
// floats or ints (SSE2 on x86-64, NEON on ARM, scalar code elsewhere) ----
namespace baseline_lanes {

/// Double lanes.
using Doubles = F64x2;
/// 64-bit integer lanes, and the masks of comparisons.
using Masks = I64x2;

/// The bits of v as integer lanes.
[[gnu::always_inline]] inline Masks as_bits(Doubles v) {
  Masks m;
  std::memcpy(&m, &v, sizeof m);
  return m;
}

/// Integer lanes' bits as double lanes.
[[gnu::always_inline]] inline Doubles as_doubles(Masks m) {
  Doubles v;
  std::memcpy(&v, &m, sizeof v);
  return v;
}

/// x in both lanes.
[[gnu::always_inline]] inline Doubles splat(double x) { return Doubles{x, x}; }

/// The lanes exchanged.
[[gnu::always_inline]] inline Doubles swap(Doubles v) { return Doubles{v[1], v[0]}; }

/// Lane by lane `mask` ? a : b.
[[gnu::always_inline]] inline Doubles select(Masks mask, Doubles a, Doubles b) {
  return as_doubles((as_bits(a) & mask) | (as_bits(b) & ~mask));
}

/// Lane by lane a < b ? a : b (b when either is NaN), the minimum of SSE.
[[gnu::always_inline]] inline Doubles min(Doubles a, Doubles b) {
#if defined(CLOTHCD_SIMD_X86)
  return _mm_min_pd(a, b);
#else
  return select(a < b, a, b);
#endif
}

/// Lane by lane a > b ? a : b (b when either is NaN), the maximum of SSE.
[[gnu::always_inline]] inline Doubles max(Doubles a, Doubles b) {
#if defined(CLOTHCD_SIMD_X86)
  return _mm_max_pd(a, b);
#else
  return select(a > b, a, b);
#endif
}

/// Lane by lane a < b, as a mask.
[[gnu::always_inline]] inline Masks less(Doubles a, Doubles b) {
#if defined(CLOTHCD_SIMD_X86)
  return as_bits(_mm_cmplt_pd(a, b));
#else
  return a < b;
#endif
}

/// True when some lane of `mask` is true (all ones).
[[gnu::always_inline]] inline bool any(Masks mask) {
#if defined(CLOTHCD_SIMD_X86)
  return _mm_movemask_pd(as_doubles(mask)) != 0;
#else
  return (mask[0] | mask[1]) != 0;
#endif
}

/// Lane by lane |v| (the sign bit cleared).
[[gnu::always_inline]] inline Doubles abs(Doubles v) {
  return as_doubles(as_bits(v) & Masks{0x7fffffffffffffffll, 0x7fffffffffffffffll});
}

/// Float or int lanes per vector.
inline constexpr int kFloatLanes = 4;
/// Float lanes.
using Floats = F32x4;
/// Integer lanes, and the masks of comparisons.
using Ints = I32x4;

/// kFloatLanes values from p (any alignment).
[[gnu::always_inline]] inline Floats load(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// kFloatLanes values from p (any alignment).
[[gnu::always_inline]] inline Ints load(const std::int32_t* p) {
  Ints v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Bit k set when lane k of `mask` is true (all ones).
[[gnu::always_inline]] inline unsigned bits(Ints mask) {
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(reinterpret_cast<__m128i>(mask))));
#else
  return static_cast<unsigned>((mask[0] & 1) | (mask[1] & 2) | (mask[2] & 4) | (mask[3] & 8));
#endif
}

/// `bits` without the bits at and above `count` (count >= 0; kFloatLanes or more keeps them all).
[[gnu::always_inline]] inline unsigned bits_below(unsigned bits, int count) {
  return bits & ((1u << (count < kFloatLanes ? count : kFloatLanes)) - 1u);
}

/// out[k] = lanes[k] + offset for the kFloatLanes bytes at `lanes`.
[[gnu::always_inline]] inline void widen_add(const std::uint8_t* lanes, std::int32_t offset, std::int32_t* out) {
  for (int k = 0; k < kFloatLanes; ++k) out[k] = lanes[k] + offset;
}

}  // namespace baseline_lanes

#if defined(CLOTHCD_SIMD_X86)
// ---- AVX2's lanes: eight floats or ints, four doubles ----
namespace avx2_lanes {

/// Float or int lanes per vector.
inline constexpr int kFloatLanes = 8;
/// Double lanes per vector.
inline constexpr int kDoubleLanes = 4;
/// Float lanes.
using Floats = F32x8;
/// Integer lanes, and the masks of comparisons.
using Ints = I32x8;

/// kFloatLanes values from p (any alignment).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Floats load(const float* p) {
  Floats v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// kFloatLanes values from p (any alignment).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Ints load(const std::int32_t* p) {
  Ints v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Bit k set when lane k of `mask` is true (all ones).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline unsigned bits(Ints mask) {
  return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(mask)));
}

/// `bits` without the bits at and above `count` (count >= 0; kFloatLanes or more keeps them all).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline unsigned bits_below(unsigned bits, int count) {
  return _bzhi_u32(bits, static_cast<unsigned>(count));
}

/// out[k] = lanes[k] + offset for the kFloatLanes bytes at `lanes` (one store).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void widen_add(const std::uint8_t* lanes, std::int32_t offset,
                                                             std::int32_t* out) {
  const __m256i wide = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(lanes)));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_add_epi32(wide, _mm256_set1_epi32(offset)));
}

/// Double lanes.
using Doubles = F64x4;
/// 64-bit integer lanes, and the masks of comparisons.
using Masks = I64x4;

/// kDoubleLanes values from p (any alignment).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles load(const double* p) { return _mm256_loadu_pd(p); }

/// p[0], p[1], p[2] and 0 (reads three doubles only).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles load3(const double* p) {
  return _mm256_maskload_pd(p, _mm256_setr_epi64x(-1, -1, -1, 0));
}

/// v to p[0 .. kDoubleLanes) (any alignment).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void store(double* p, Doubles v) { _mm256_storeu_pd(p, v); }

/// The first three lanes of v to p[0], p[1], p[2] (writes three doubles only).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void store3(double* p, Doubles v) {
  _mm256_maskstore_pd(p, _mm256_setr_epi64x(-1, -1, -1, 0), v);
}

/// Rows of three (the first three lanes of rows[0..3]) as columns: lane l of out[c] is lane c of rows[l].
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline void transpose3(const Doubles rows[4], Doubles out[3]) {
  const __m256d lo01 = _mm256_unpacklo_pd(rows[0], rows[1]), hi01 = _mm256_unpackhi_pd(rows[0], rows[1]);
  const __m256d lo23 = _mm256_unpacklo_pd(rows[2], rows[3]), hi23 = _mm256_unpackhi_pd(rows[2], rows[3]);
  out[0] = _mm256_permute2f128_pd(lo01, lo23, 0x20);
  out[1] = _mm256_permute2f128_pd(hi01, hi23, 0x20);
  out[2] = _mm256_permute2f128_pd(lo01, lo23, 0x31);
}

/// x in every lane.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles splat(double x) { return _mm256_set1_pd(x); }

/// The lanes (x, y, z, w).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles make(double x, double y, double z, double w) {
  return _mm256_setr_pd(x, y, z, w);
}

/// Lane by lane a < b ? a : b (b when either is NaN), the minimum of SSE.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles min(Doubles a, Doubles b) { return _mm256_min_pd(a, b); }

/// Lane by lane a > b ? a : b (b when either is NaN), the maximum of SSE.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles max(Doubles a, Doubles b) { return _mm256_max_pd(a, b); }

/// Lane by lane `mask` ? a : b.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles select(Masks mask, Doubles a, Doubles b) {
  return _mm256_blendv_pd(b, a, reinterpret_cast<__m256d>(mask));
}

/// The square root of every lane.
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline Doubles sqrt(Doubles v) { return _mm256_sqrt_pd(v); }

/// Every lane rounded toward zero to a 32-bit integer (lanes beyond the int range or NaN give INT_MIN).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline I32x4 truncate(Doubles v) {
  return reinterpret_cast<I32x4>(_mm256_cvttpd_epi32(v));
}

/// Bit k set when lane k of `mask` is true (all ones).
[[gnu::always_inline]] CLOTHCD_SIMD_AVX2 inline unsigned bits(Masks mask) {
  return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(mask)));
}

}  // namespace avx2_lanes

#endif

// ---- lanes as plain arrays: kernels written lane by lane, each loop vectorized by the compiler at the level it is
// compiled for (the same IEEE operations in the same order at every level) ----

/// N doubles, one per lane, with the element-wise operations of the kernels written lane by lane.
template <int N>
struct LaneArray {
  double v[N];
  /// Lane l.
  [[gnu::always_inline]] double& operator[](int l) { return v[l]; }
  /// Lane l.
  [[gnu::always_inline]] double operator[](int l) const { return v[l]; }
};

/// Lane by lane a + b.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator+(const LaneArray<N>& a, const LaneArray<N>& b) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = a.v[l] + b.v[l];
  return r;
}
/// Lane by lane a - b.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator-(const LaneArray<N>& a, const LaneArray<N>& b) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = a.v[l] - b.v[l];
  return r;
}
/// Lane by lane -a.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator-(const LaneArray<N>& a) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = -a.v[l];
  return r;
}
/// Lane by lane a b.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator*(const LaneArray<N>& a, const LaneArray<N>& b) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = a.v[l] * b.v[l];
  return r;
}
/// Every lane of a times s (s on the left of each product).
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator*(double s, const LaneArray<N>& a) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = s * a.v[l];
  return r;
}
/// Every lane of a divided by s.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> operator/(const LaneArray<N>& a, double s) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = a.v[l] / s;
  return r;
}
/// Lane by lane std::min(a, b) (b < a ? b : a).
template <int N>
[[gnu::always_inline]] inline LaneArray<N> lane_min(const LaneArray<N>& a, const LaneArray<N>& b) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = b.v[l] < a.v[l] ? b.v[l] : a.v[l];
  return r;
}
/// Lane by lane std::max(a, b) (a < b ? b : a).
template <int N>
[[gnu::always_inline]] inline LaneArray<N> lane_max(const LaneArray<N>& a, const LaneArray<N>& b) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = a.v[l] < b.v[l] ? b.v[l] : a.v[l];
  return r;
}
/// The square root of every lane.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> lane_sqrt(const LaneArray<N>& a) {
  LaneArray<N> r;
  for (int l = 0; l < N; ++l) r.v[l] = std::sqrt(a.v[l]);
  return r;
}

/// A 3-vector per lane: c[axis] holds the axis' coordinate of every lane.
template <int N>
struct LaneVector3 {
  LaneArray<N> c[3];
};

/// Lane by lane a + b.
template <int N>
[[gnu::always_inline]] inline LaneVector3<N> operator+(const LaneVector3<N>& a, const LaneVector3<N>& b) {
  return {{a.c[0] + b.c[0], a.c[1] + b.c[1], a.c[2] + b.c[2]}};
}
/// Lane by lane a - b.
template <int N>
[[gnu::always_inline]] inline LaneVector3<N> operator-(const LaneVector3<N>& a, const LaneVector3<N>& b) {
  return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}};
}
/// Every lane's vector times s.
template <int N>
[[gnu::always_inline]] inline LaneVector3<N> operator*(double s, const LaneVector3<N>& a) {
  return {{s * a.c[0], s * a.c[1], s * a.c[2]}};
}
/// Every lane's vector divided by s.
template <int N>
[[gnu::always_inline]] inline LaneVector3<N> operator/(const LaneVector3<N>& a, double s) {
  return {{a.c[0] / s, a.c[1] / s, a.c[2] / s}};
}
/// Lane by lane a . b in Eigen's order, (a0 b0 + a1 b1) + a2 b2.
template <int N>
[[gnu::always_inline]] inline LaneArray<N> dot(const LaneVector3<N>& a, const LaneVector3<N>& b) {
  return (a.c[0] * b.c[0] + a.c[1] * b.c[1]) + a.c[2] * b.c[2];
}
/// Lane by lane a . s for one direction s[0..3), (s0 a0 + s1 a1) + s2 a2 (the products commute exactly).
template <int N>
[[gnu::always_inline]] inline LaneArray<N> dot(const LaneVector3<N>& a, const double* s) {
  return (s[0] * a.c[0] + s[1] * a.c[1]) + s[2] * a.c[2];
}
/// Lane by lane a x b.
template <int N>
[[gnu::always_inline]] inline LaneVector3<N> cross(const LaneVector3<N>& a, const LaneVector3<N>& b) {
  return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2], a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}
/// Lane by lane |a| (the square root of dot(a, a)).
template <int N>
[[gnu::always_inline]] inline LaneArray<N> norm(const LaneVector3<N>& a) {
  return lane_sqrt(dot(a, a));
}

}  // namespace clothcd::simd
