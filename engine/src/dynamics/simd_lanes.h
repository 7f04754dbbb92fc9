// Lanes: four doubles processed together, the arithmetic of the wide
// contact solver (dynamics/wide_contact_solver.cpp).
//
// Two implementations of the same operations, chosen at build time:
// * AVX2 (`TALUS_SIMD_AVX2` defined, set by the CMake option TALUS_SIMD=AVX2
//   for the one file that includes this): one __m256d per value;
// * scalar (the portable default): four doubles and a loop per operation.
//
// Both do the same IEEE operations in the same order lane by lane (add,
// subtract, multiply, max, min, compare, select; no fused multiply-add: the
// AVX2 file is compiled without -mfma and with -ffp-contract=off), and max /
// min / compare follow the instructions' rules exactly ((a > b) ? a : b,
// (a < b) ? a : b, ordered compares), so the two builds give bit-identical
// results. Each lane's result depends on that lane's inputs alone.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(TALUS_SIMD_AVX2)
#include <immintrin.h>
#endif

namespace talus::lanes {

inline constexpr int kWidth = 4;

#if defined(TALUS_SIMD_AVX2)

/// Four doubles.
struct Wide {
  __m256d v;
};
/// Four booleans (all bits set in a true lane).
struct Mask {
  __m256d v;
};

inline Wide Load(const double* p) { return {_mm256_load_pd(p)}; }
inline void Store(double* p, Wide a) { _mm256_store_pd(p, a.v); }
inline Wide Splat(double x) { return {_mm256_set1_pd(x)}; }
inline Wide Zero() { return {_mm256_setzero_pd()}; }
inline Wide operator+(Wide a, Wide b) { return {_mm256_add_pd(a.v, b.v)}; }
inline Wide operator-(Wide a, Wide b) { return {_mm256_sub_pd(a.v, b.v)}; }
inline Wide operator*(Wide a, Wide b) { return {_mm256_mul_pd(a.v, b.v)}; }
inline Wide operator/(Wide a, Wide b) { return {_mm256_div_pd(a.v, b.v)}; }
inline Wide operator-(Wide a) { return {_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0))}; }
/// (a > b) ? a : b per lane (the instruction's rule).
inline Wide Max(Wide a, Wide b) { return {_mm256_max_pd(a.v, b.v)}; }
/// (a < b) ? a : b per lane.
inline Wide Min(Wide a, Wide b) { return {_mm256_min_pd(a.v, b.v)}; }
inline Wide Abs(Wide a) { return {_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)}; }
inline Mask GreaterEqual(Wide a, Wide b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GE_OQ)}; }
inline Mask operator&(Mask a, Mask b) { return {_mm256_and_pd(a.v, b.v)}; }
inline Mask operator!(Mask a) { return {_mm256_xor_pd(a.v, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)))}; }
/// m ? a : b per lane.
inline Wide Select(Mask m, Wide a, Wide b) { return {_mm256_blendv_pd(b.v, a.v, m.v)}; }
inline bool Any(Mask m) { return _mm256_movemask_pd(m.v) != 0; }
/// Lane i of out[k] = rows[i][k], k < 6: four rows of six contiguous
/// doubles (a solver body's v and w) turned into six lanes. Two 4x4
/// transposes of unaligned loads at offsets 0 and 2 (both inside the row).
inline void Transpose6(const double* const (&rows)[kWidth], Wide (&out)[6]) {
  const auto transpose = [](__m256d a0, __m256d a1, __m256d a2, __m256d a3, __m256d(&r)[4]) {
    const __m256d t0 = _mm256_unpacklo_pd(a0, a1);
    const __m256d t1 = _mm256_unpackhi_pd(a0, a1);
    const __m256d t2 = _mm256_unpacklo_pd(a2, a3);
    const __m256d t3 = _mm256_unpackhi_pd(a2, a3);
    r[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
    r[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    r[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
    r[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
  };
  __m256d low[4];
  __m256d high[4];
  transpose(_mm256_loadu_pd(rows[0]), _mm256_loadu_pd(rows[1]), _mm256_loadu_pd(rows[2]),
            _mm256_loadu_pd(rows[3]), low);
  transpose(_mm256_loadu_pd(rows[0] + 2), _mm256_loadu_pd(rows[1] + 2), _mm256_loadu_pd(rows[2] + 2),
            _mm256_loadu_pd(rows[3] + 2), high);
  for (int k = 0; k < 4; ++k) out[k].v = low[k];
  out[4].v = high[2];
  out[5].v = high[3];
}

/// The inverse of Transpose6 for the lanes set in `bits`: rows[i][k] =
/// lane i of in[k]; other rows are not written.
inline void Untranspose6(const Wide (&in)[6], unsigned bits, double* const (&rows)[kWidth]) {
  // Rows [x y z wx] from in[0..3] and [z wx wy wz] from in[2..5]: the
  // same transpose (it is its own inverse), stored unaligned, overlapping.
  const auto transpose = [](__m256d a0, __m256d a1, __m256d a2, __m256d a3, __m256d(&r)[4]) {
    const __m256d t0 = _mm256_unpacklo_pd(a0, a1);
    const __m256d t1 = _mm256_unpackhi_pd(a0, a1);
    const __m256d t2 = _mm256_unpacklo_pd(a2, a3);
    const __m256d t3 = _mm256_unpackhi_pd(a2, a3);
    r[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
    r[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    r[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
    r[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
  };
  __m256d low[4];
  __m256d high[4];
  transpose(in[0].v, in[1].v, in[2].v, in[3].v, low);
  transpose(in[2].v, in[3].v, in[4].v, in[5].v, high);
  for (int i = 0; i < kWidth; ++i) {
    if (((bits >> i) & 1u) == 0) continue;
    _mm256_storeu_pd(rows[i], low[i]);
    _mm256_storeu_pd(rows[i] + 2, high[i]);
  }
}

/// A mask from four flags in the low bits of `bits` (lane i = bit i).
inline Mask MaskFromBits(unsigned bits) {
  const __m256i lane = _mm256_set_epi64x(8, 4, 2, 1);
  const __m256i set = _mm256_and_si256(_mm256_set1_epi64x(static_cast<std::int64_t>(bits)), lane);
  return {_mm256_castsi256_pd(_mm256_cmpeq_epi64(set, lane))};
}

#else

struct Wide {
  double v[kWidth];
};
struct Mask {
  bool v[kWidth];
};

template <typename F>
inline Wide Map(F f) {
  Wide r;
  for (int i = 0; i < kWidth; ++i) r.v[i] = f(i);
  return r;
}
inline Wide Load(const double* p) {
  Wide r;
  std::memcpy(r.v, p, sizeof r.v);
  return r;
}
inline void Store(double* p, Wide a) { std::memcpy(p, a.v, sizeof a.v); }
inline Wide Splat(double x) {
  return Map([x](int) { return x; });
}
inline Wide Zero() { return Splat(0.0); }
inline Wide operator+(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] + b.v[i]; });
}
inline Wide operator-(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] - b.v[i]; });
}
inline Wide operator*(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] * b.v[i]; });
}
inline Wide operator/(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] / b.v[i]; });
}
inline Wide operator-(Wide a) {
  return Map([&](int i) { return -a.v[i]; });
}
inline Wide Max(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] > b.v[i] ? a.v[i] : b.v[i]; });
}
inline Wide Min(Wide a, Wide b) {
  return Map([&](int i) { return a.v[i] < b.v[i] ? a.v[i] : b.v[i]; });
}
inline Wide Abs(Wide a) {
  // Clears the sign bit, as the AVX2 and-not does (fabs would too; this
  // keeps the two builds' definitions visibly the same).
  return Map([&](int i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &a.v[i], sizeof bits);
    bits &= ~(std::uint64_t{1} << 63);
    double r = 0.0;
    std::memcpy(&r, &bits, sizeof r);
    return r;
  });
}
inline Mask GreaterEqual(Wide a, Wide b) {
  Mask m;
  for (int i = 0; i < kWidth; ++i) m.v[i] = a.v[i] >= b.v[i];
  return m;
}
inline Mask operator&(Mask a, Mask b) {
  Mask m;
  for (int i = 0; i < kWidth; ++i) m.v[i] = a.v[i] && b.v[i];
  return m;
}
inline Mask operator!(Mask a) {
  Mask m;
  for (int i = 0; i < kWidth; ++i) m.v[i] = !a.v[i];
  return m;
}
inline Wide Select(Mask m, Wide a, Wide b) {
  return Map([&](int i) { return m.v[i] ? a.v[i] : b.v[i]; });
}
inline bool Any(Mask m) { return m.v[0] || m.v[1] || m.v[2] || m.v[3]; }
inline void Transpose6(const double* const (&rows)[kWidth], Wide (&out)[6]) {
  for (int k = 0; k < 6; ++k) {
    for (int i = 0; i < kWidth; ++i) out[k].v[i] = rows[i][k];
  }
}
inline void Untranspose6(const Wide (&in)[6], unsigned bits, double* const (&rows)[kWidth]) {
  for (int i = 0; i < kWidth; ++i) {
    if (((bits >> i) & 1u) == 0) continue;
    for (int k = 0; k < 6; ++k) rows[i][k] = in[k].v[i];
  }
}
inline Mask MaskFromBits(unsigned bits) {
  Mask m;
  for (int i = 0; i < kWidth; ++i) m.v[i] = ((bits >> i) & 1u) != 0;
  return m;
}

#endif

/// Dot product of two 3-vectors of lanes in Eigen's order for a Vector3d
/// ((x + y) + z: one packet of two, reduced, then the third; checked on
/// 1e5 random pairs), so a lane gives the scalar solver's bits.
inline Wide Dot(Wide ax, Wide ay, Wide az, Wide bx, Wide by, Wide bz) {
  return (ax * bx + ay * by) + az * bz;
}

}  // namespace talus::lanes
