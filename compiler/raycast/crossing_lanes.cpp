#include "compiler/raycast/crossing_lanes.hpp"

#include "compiler/raycast/plane_blocks.hpp"  // kPlaneU, kPlaneV

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace walk::compiler {

#if defined(__x86_64__)
bool crossing_lanes_available() {
  static const bool available = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  return available;
}

__attribute__((target("avx512f,avx512vl,popcnt"))) int gather_crossings(const CrossingLanes& lanes,
                                                                        std::uint32_t first,
                                                                        const std::uint32_t end[3],
                                                                        const CrossingRay& r,
                                                                        const Crossings& out) {
  const __m512d t_enter = _mm512_set1_pd(r.t_enter), tmin = _mm512_set1_pd(r.tmin);
  const __m512d t_exit = _mm512_set1_pd(r.t_exit), limit = _mm512_set1_pd(r.limit);
  // One pass over the block's listings of all three axes, eight at a time: each lane takes its axis' origin,
  // inverse and in-plane components by permutation (the axes' listings are consecutive ranges), instead of
  // a loop per axis that paid its set-up and a partly empty vector three times per block.
  const __m512d o_k = _mm512_setr_pd(r.o[0], r.o[1], r.o[2], 0, 0, 0, 0, 0),
                inv_k = _mm512_setr_pd(r.inv[0], r.inv[1], r.inv[2], 0, 0, 0, 0, 0);
  const __m512d o_u = _mm512_setr_pd(r.o[kPlaneU[0]], r.o[kPlaneU[1]], r.o[kPlaneU[2]], 0, 0, 0, 0, 0);
  const __m512d d_u = _mm512_setr_pd(r.d[kPlaneU[0]], r.d[kPlaneU[1]], r.d[kPlaneU[2]], 0, 0, 0, 0, 0);
  const __m512d o_v = _mm512_setr_pd(r.o[kPlaneV[0]], r.o[kPlaneV[1]], r.o[kPlaneV[2]], 0, 0, 0, 0, 0);
  const __m512d d_v = _mm512_setr_pd(r.d[kPlaneV[0]], r.d[kPlaneV[1]], r.d[kPlaneV[2]], 0, 0, 0, 0, 0);
  // Axes the ray moves along: the planes of the others are never crossed.
  const __mmask8 moving =
      static_cast<__mmask8>((r.d[0] != 0.0 ? 1 : 0) | (r.d[1] != 0.0 ? 2 : 0) | (r.d[2] != 0.0 ? 4 : 0));
  const __m512i lane = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
  const __m512i end0 = _mm512_set1_epi64(end[0]), end1 = _mm512_set1_epi64(end[1]);
  const __m512i one = _mm512_set1_epi64(1);
  // The zero-masked forms of the permutes, shift and narrowing below (all lanes kept): the plain ones start
  // from an undefined register, which GCC 12 reports as maybe uninitialized.
  // The arrays' addresses in locals: the compress-stores may write anywhere, so the compiler would reload
  // them from the vectors and from `out` on every iteration.
  const double *coord = lanes.coord.data(), *u0 = lanes.u0.data(), *u1 = lanes.u1.data();
  const double *v0 = lanes.v0.data(), *v1 = lanes.v1.data();
  double *out_t = out.t, *out_u = out.pu, *out_v = out.pv;
  std::uint32_t* out_index = out.index;
  std::uint64_t* out_items = out.items;
  const std::uint64_t* items = lanes.items.data();
  int n = 0;
  for (std::uint32_t j = first; j < end[2]; j += 8) {
    const std::uint32_t left = end[2] - j;
    const __m512i index = _mm512_add_epi64(_mm512_set1_epi64(j), lane);
    // Axis of each lane: 0, plus one past end[0], plus one past end[1].
    __m512i axis = _mm512_mask_add_epi64(_mm512_setzero_si512(), _mm512_cmpge_epu64_mask(index, end0),
                                         _mm512_setzero_si512(), one);
    axis = _mm512_mask_add_epi64(axis, _mm512_cmpge_epu64_mask(index, end1), axis, one);
    const __mmask8 in_block = left >= 8 ? 0xFF : static_cast<__mmask8>((1u << left) - 1);
    // Lanes whose axis the ray moves along: bit `axis` of `moving`.
    const __mmask8 live =
        static_cast<__mmask8>(in_block & _mm512_test_epi64_mask(_mm512_maskz_sllv_epi64(0xFF, one, axis),
                                                                _mm512_set1_epi64(moving)));
    const __m512d ok = _mm512_maskz_permutexvar_pd(0xFF, axis, o_k),
                  inv = _mm512_maskz_permutexvar_pd(0xFF, axis, inv_k);
    const __m512d t = _mm512_mul_pd(_mm512_sub_pd(_mm512_maskz_loadu_pd(live, coord + j), ok), inv);
    const __m512d pu = _mm512_add_pd(_mm512_maskz_permutexvar_pd(0xFF, axis, o_u),
                                     _mm512_mul_pd(t, _mm512_maskz_permutexvar_pd(0xFF, axis, d_u)));
    const __m512d pv = _mm512_add_pd(_mm512_maskz_permutexvar_pd(0xFF, axis, o_v),
                                     _mm512_mul_pd(t, _mm512_maskz_permutexvar_pd(0xFF, axis, d_v)));
    // Ordered comparisons: a NaN t or point fails every one, as in the scalar walk.
    __mmask8 m = _mm512_mask_cmp_pd_mask(live, t, t_enter, _CMP_GE_OQ);
    m = _mm512_mask_cmp_pd_mask(m, t, tmin, _CMP_GT_OQ);
    m = _mm512_mask_cmp_pd_mask(m, t, t_exit, _CMP_LE_OQ);
    m = _mm512_mask_cmp_pd_mask(m, t, limit, _CMP_LT_OQ);
    m = _mm512_mask_cmp_pd_mask(m, pu, _mm512_maskz_loadu_pd(live, u0 + j), _CMP_GE_OQ);
    m = _mm512_mask_cmp_pd_mask(m, pu, _mm512_maskz_loadu_pd(live, u1 + j), _CMP_LE_OQ);
    m = _mm512_mask_cmp_pd_mask(m, pv, _mm512_maskz_loadu_pd(live, v0 + j), _CMP_GE_OQ);
    m = _mm512_mask_cmp_pd_mask(m, pv, _mm512_maskz_loadu_pd(live, v1 + j), _CMP_LE_OQ);
    // Compressed in registers and stored whole, with no branch on whether any lane crossed: a group of eight
    // that crosses nothing is as common as one that does (the stores past n are overwritten or never read).
    // A compress straight to memory is microcoded on AMD Zen 4.
    _mm512_storeu_pd(out_t + n, _mm512_maskz_compress_pd(m, t));
    _mm512_storeu_pd(out_u + n, _mm512_maskz_compress_pd(m, pu));
    _mm512_storeu_pd(out_v + n, _mm512_maskz_compress_pd(m, pv));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out_index + n),
                        _mm256_maskz_compress_epi32(m, _mm512_maskz_cvtepi64_epi32(0xFF, index)));
    _mm512_storeu_si512(out_items + n,
                        _mm512_maskz_compress_epi64(m, _mm512_maskz_loadu_epi64(live, items + j)));
    n += __builtin_popcount(m);
  }
  return n;
}
#else
bool crossing_lanes_available() {
  return false;
}
int gather_crossings(const CrossingLanes&, std::uint32_t, const std::uint32_t[3], const CrossingRay&,
                     const Crossings&) {
  return 0;
}
#endif

}  // namespace walk::compiler
