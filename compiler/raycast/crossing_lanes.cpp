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
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  int n = 0;
  std::uint32_t lo = first;
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t hi = end[k];
    if (r.d[k] == 0.0) {  // never crosses these planes
      lo = hi;
      continue;
    }
    const __m512d ok = _mm512_set1_pd(r.o[k]), inv = _mm512_set1_pd(r.inv[k]);
    const __m512d ou = _mm512_set1_pd(r.o[kPlaneU[k]]), du = _mm512_set1_pd(r.d[kPlaneU[k]]);
    const __m512d ov = _mm512_set1_pd(r.o[kPlaneV[k]]), dv = _mm512_set1_pd(r.d[kPlaneV[k]]);
    for (std::uint32_t j = lo; j < hi; j += 8) {
      const std::uint32_t left = hi - j;
      const __mmask8 live = left >= 8 ? 0xFF : static_cast<__mmask8>((1u << left) - 1);
      const __m512d t =
          _mm512_mul_pd(_mm512_sub_pd(_mm512_maskz_loadu_pd(live, lanes.coord.data() + j), ok), inv);
      const __m512d pu = _mm512_add_pd(ou, _mm512_mul_pd(t, du));
      const __m512d pv = _mm512_add_pd(ov, _mm512_mul_pd(t, dv));
      // Ordered comparisons: a NaN t or point fails every one, as in the scalar walk.
      __mmask8 m = _mm512_mask_cmp_pd_mask(live, t, t_enter, _CMP_GE_OQ);
      m = _mm512_mask_cmp_pd_mask(m, t, tmin, _CMP_GT_OQ);
      m = _mm512_mask_cmp_pd_mask(m, t, t_exit, _CMP_LE_OQ);
      m = _mm512_mask_cmp_pd_mask(m, t, limit, _CMP_LT_OQ);
      m = _mm512_mask_cmp_pd_mask(m, pu, _mm512_maskz_loadu_pd(live, lanes.u0.data() + j), _CMP_GE_OQ);
      m = _mm512_mask_cmp_pd_mask(m, pu, _mm512_maskz_loadu_pd(live, lanes.u1.data() + j), _CMP_LE_OQ);
      m = _mm512_mask_cmp_pd_mask(m, pv, _mm512_maskz_loadu_pd(live, lanes.v0.data() + j), _CMP_GE_OQ);
      m = _mm512_mask_cmp_pd_mask(m, pv, _mm512_maskz_loadu_pd(live, lanes.v1.data() + j), _CMP_LE_OQ);
      if (m == 0) continue;
      _mm512_mask_compressstoreu_pd(out.t + n, m, t);
      _mm512_mask_compressstoreu_pd(out.pu + n, m, pu);
      _mm512_mask_compressstoreu_pd(out.pv + n, m, pv);
      _mm256_mask_compressstoreu_epi32(out.index + n, m,
                                       _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(j)), lane));
      n += __builtin_popcount(m);
    }
    lo = hi;
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
