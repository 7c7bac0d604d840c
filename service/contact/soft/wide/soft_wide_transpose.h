// Columns of a few rows of floats as SIMD batches: lane l of batch k is
// row l's float k. The float path gathers each lane's body (WideBody, 18
// floats) into batches field by field; copied one float at a time through
// a buffer, the gather's and the scatter's lines counted 1.1M instructions
// of a float pyramid step, and the transposes saved 0.37M of it
// (BENCHMARKS.md, "soft: the float path"). A transpose in registers moves
// the same floats, so every lane holds the same values bit for bit.
#pragma once

#include <cstddef>
#include <type_traits>

#include <xsimd/xsimd.hpp>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace contactsim {
namespace wide {

// B's lanes as AVX's 8 or SSE's 4 (xsimd's later x86 sets derive from
// those), where this file is compiled for them.
#if defined(__AVX__)
constexpr bool kAvxBuild = true;
#else
constexpr bool kAvxBuild = false;
#endif
#if defined(__SSE2__)
constexpr bool kSseBuild = true;
#else
constexpr bool kSseBuild = false;
#endif
template <class B, class Family>
constexpr bool LanesOf(size_t lanes) {
  return B::size == lanes && std::is_base_of<Family, typename B::arch_type>::value;
}
template <class B>
constexpr bool IsAvx8() {
  if constexpr (kAvxBuild) return LanesOf<B, xsimd::avx>(8);
  return false;
}
template <class B>
constexpr bool IsSse4() {
  if constexpr (kSseBuild) return LanesOf<B, xsimd::sse2>(4);
  return false;
}
// Whether B's lanes transpose in registers.
template <class B>
constexpr bool TransposesInRegisters() {
  return IsAvx8<B>() || IsSse4<B>();
}

#if defined(__AVX__)
// An 8x8 transpose in registers: lane l of r_k becomes lane k of r_l.
// Written out: as loops over arrays GCC kept the registers on the stack.
inline __attribute__((always_inline)) void Transpose8x8(__m256& r0, __m256& r1, __m256& r2, __m256& r3, __m256& r4,
                                                        __m256& r5, __m256& r6, __m256& r7) {
  const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
  const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
  const __m256 t4 = _mm256_unpacklo_ps(r4, r5), t5 = _mm256_unpackhi_ps(r4, r5);
  const __m256 t6 = _mm256_unpacklo_ps(r6, r7), t7 = _mm256_unpackhi_ps(r6, r7);
  // per 128-bit half: s0..s3 columns 0..3 (4..7) of rows 0..3, s4..s7 of rows 4..7
  const __m256 s0 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 s1 = _mm256_shuffle_ps(t0, t2, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 s2 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 s3 = _mm256_shuffle_ps(t1, t3, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 s4 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 s5 = _mm256_shuffle_ps(t4, t6, _MM_SHUFFLE(3, 2, 3, 2));
  const __m256 s6 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(1, 0, 1, 0));
  const __m256 s7 = _mm256_shuffle_ps(t5, t7, _MM_SHUFFLE(3, 2, 3, 2));
  r0 = _mm256_permute2f128_ps(s0, s4, 0x20), r4 = _mm256_permute2f128_ps(s0, s4, 0x31);
  r1 = _mm256_permute2f128_ps(s1, s5, 0x20), r5 = _mm256_permute2f128_ps(s1, s5, 0x31);
  r2 = _mm256_permute2f128_ps(s2, s6, 0x20), r6 = _mm256_permute2f128_ps(s2, s6, 0x31);
  r3 = _mm256_permute2f128_ps(s3, s7, 0x20), r7 = _mm256_permute2f128_ps(s3, s7, 0x31);
}
#endif

// out[k], k < B::size: lane l is rows[l][offset + k]; every row has at
// least offset + B::size floats. Only where TransposesInRegisters<B>().
template <class B>
inline __attribute__((always_inline)) void LoadColumns(const float* const* rows, int offset, B* out) {
#if defined(__AVX__)
  if constexpr (IsAvx8<B>()) {
    __m256 r0 = _mm256_loadu_ps(rows[0] + offset), r1 = _mm256_loadu_ps(rows[1] + offset);
    __m256 r2 = _mm256_loadu_ps(rows[2] + offset), r3 = _mm256_loadu_ps(rows[3] + offset);
    __m256 r4 = _mm256_loadu_ps(rows[4] + offset), r5 = _mm256_loadu_ps(rows[5] + offset);
    __m256 r6 = _mm256_loadu_ps(rows[6] + offset), r7 = _mm256_loadu_ps(rows[7] + offset);
    Transpose8x8(r0, r1, r2, r3, r4, r5, r6, r7);
    out[0] = B(r0), out[1] = B(r1), out[2] = B(r2), out[3] = B(r3);
    out[4] = B(r4), out[5] = B(r5), out[6] = B(r6), out[7] = B(r7);
    return;
  }
#endif
#if defined(__SSE2__)
  if constexpr (IsSse4<B>()) {
    __m128 r0 = _mm_loadu_ps(rows[0] + offset), r1 = _mm_loadu_ps(rows[1] + offset);
    __m128 r2 = _mm_loadu_ps(rows[2] + offset), r3 = _mm_loadu_ps(rows[3] + offset);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    out[0] = B(r0), out[1] = B(r1), out[2] = B(r2), out[3] = B(r3);
    return;
  }
#endif
  (void)rows, (void)offset, (void)out;
}

// The inverse for six batches c[0..5]: row l's floats 0..5 are lane l of
// c[0..5], written only where write[l] != 0 (the float after them is left
// as it was). Only where TransposesInRegisters<B>().
template <class B>
inline __attribute__((always_inline)) void StoreRows6(const B* c, float* const* rows, const unsigned char* write) {
#if defined(__AVX__)
  if constexpr (IsAvx8<B>()) {
    __m256 r0 = c[0], r1 = c[1], r2 = c[2], r3 = c[3], r4 = c[4], r5 = c[5];
    __m256 r6 = _mm256_setzero_ps(), r7 = _mm256_setzero_ps();
    Transpose8x8(r0, r1, r2, r3, r4, r5, r6, r7);
    const __m256 row[8] = {r0, r1, r2, r3, r4, r5, r6, r7};
    for (int l = 0; l < 8; ++l) {
      if (write[l] == 0) continue;
      _mm_storeu_ps(rows[l], _mm256_castps256_ps128(row[l]));
      _mm_storel_pi(reinterpret_cast<__m64*>(rows[l] + 4), _mm256_extractf128_ps(row[l], 1));
    }
    return;
  }
#endif
#if defined(__SSE2__)
  if constexpr (IsSse4<B>()) {
    __m128 r0 = c[0], r1 = c[1], r2 = c[2], r3 = c[3];
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    __m128 q0 = c[4], q1 = c[5], q2 = _mm_setzero_ps(), q3 = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(q0, q1, q2, q3);
    const __m128 head[4] = {r0, r1, r2, r3}, rest[4] = {q0, q1, q2, q3};
    for (int l = 0; l < 4; ++l) {
      if (write[l] == 0) continue;
      _mm_storeu_ps(rows[l], head[l]);
      _mm_storel_pi(reinterpret_cast<__m64*>(rows[l] + 4), rest[l]);
    }
    return;
  }
#endif
  (void)c, (void)rows, (void)write;
}

}  // namespace wide
}  // namespace contactsim
