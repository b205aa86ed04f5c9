// SPDX-License-Identifier: Apache-2.0
// STRIPES' Boussinesq closure integral (boussinesq_sum.hpp): the SSE2 strip terms and the AVX2 /
// SSE2 logarithm sums, each in a fixed order so that results do not depend on the CPU.
#include "normal/boussinesq_sum.hpp"

#include <algorithm>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "normal/normal_internal.hpp"

namespace railtab::detail {

namespace {

#if defined(__x86_64__) && defined(__GNUC__)
#define RAILTAB_STRIPES_AVX2 1
// fast_log (normal_internal.hpp) on four lanes with AVX2, bit for bit the same operations (no FMA:
// the target adds AVX2 only); lanes that are not positive normal numbers go through fast_log.
__attribute__((target("avx2"))) inline __m256d fast_log_pd4(__m256d x) {
  const __m256d ok = _mm256_and_pd(_mm256_cmp_pd(x, _mm256_set1_pd(0x1p-1022), _CMP_GE_OQ),
                                   _mm256_cmp_pd(x, _mm256_set1_pd(0x1.fffffffffffffp+1023),
                                                 _CMP_LE_OQ));
  if (_mm256_movemask_pd(ok) != 15) {
    double t[4];
    _mm256_storeu_pd(t, x);
    return _mm256_set_pd(fast_log(t[3]), fast_log(t[2]), fast_log(t[1]), fast_log(t[0]));
  }
  const __m256i bits = _mm256_castpd_si256(x);
  const __m256i eb =
      _mm256_or_si256(_mm256_srli_epi64(bits, 52), _mm256_set1_epi64x(0x4330000000000000LL));
  __m256d e = _mm256_sub_pd(_mm256_castsi256_pd(eb), _mm256_set1_pd(4503599627370496.0 + 1023.0));
  __m256d m = _mm256_castsi256_pd(
      _mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x(0x000fffffffffffffLL)),
                      _mm256_set1_epi64x(0x3ff0000000000000LL)));
  const __m256d big = _mm256_cmp_pd(m, _mm256_set1_pd(1.4142135623730951), _CMP_GT_OQ);
  m = _mm256_or_pd(_mm256_and_pd(big, _mm256_mul_pd(m, _mm256_set1_pd(0.5))),
                   _mm256_andnot_pd(big, m));
  e = _mm256_add_pd(e, _mm256_and_pd(big, _mm256_set1_pd(1.0)));
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d u = _mm256_div_pd(_mm256_sub_pd(m, one), _mm256_add_pd(m, one));
  const __m256d u2 = _mm256_mul_pd(u, u);
  __m256d r = _mm256_set1_pd(1.0 / 17.0);
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 15.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 13.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 11.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 9.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 7.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 5.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), _mm256_set1_pd(1.0 / 3.0));
  r = _mm256_add_pd(_mm256_mul_pd(r, u2), one);
  return _mm256_add_pd(_mm256_mul_pd(e, _mm256_set1_pd(0.6931471805599453)),
                       _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(2.0), u), r));
}

// sum1 += c1[i] ln a1[i], sum2 += c2[i] ln a2[i] in order for i < m (m a multiple of 4).
__attribute__((target("avx2"))) void log_sums_avx2(const double* a1, const double* c1,
                                                   const double* a2, const double* c2, int m,
                                                   double* sum1, double* sum2) {
  double s1 = *sum1, s2 = *sum2;
  for (int i = 0; i < m; i += 4) {
    double u1[4], u2[4];
    _mm256_storeu_pd(u1, _mm256_mul_pd(fast_log_pd4(_mm256_loadu_pd(a1 + i)),
                                       _mm256_loadu_pd(c1 + i)));
    _mm256_storeu_pd(u2, _mm256_mul_pd(fast_log_pd4(_mm256_loadu_pd(a2 + i)),
                                       _mm256_loadu_pd(c2 + i)));
    s1 += u1[0];
    s2 += u2[0];
    s1 += u1[1];
    s2 += u2[1];
    s1 += u1[2];
    s2 += u2[2];
    s1 += u1[3];
    s2 += u2[3];
  }
  *sum1 = s1;
  *sum2 = s2;
}

bool have_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}
#endif

}  // namespace

void BoussinesqSum::add_strips(const double* A, const double* a, int n, double s_lo,
                               double width, double s_ref) {
#if defined(__SSE2__)
    const double w = width;
    const __m128d vw = _mm_set1_pd(w);
    const __m128d sign = _mm_set1_pd(-0.0);
    int k = 0;
    while (k < n) {
      const double y0 = s_lo + (k + 0.5) * width - s_ref;
      const double ay0 = std::abs(y0);
      if (k + 1 < n && a[k] > 0.0 && a[k + 1] > 0.0 && !(ay0 < 6.0 * w)) {
        const double y1 = s_lo + (k + 1 + 0.5) * width - s_ref;
        const double ay1 = std::abs(y1);
        if (!(ay1 < 6.0 * w)) {  // two far strips
          const __m128d va = _mm_loadu_pd(a + k);
          const __m128d vA = _mm_loadu_pd(A + k);
          const __m128d vay = _mm_set_pd(ay1, ay0);
          const __m128d r =
              _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(va, va), _mm_mul_pd(vay, vay)));
          const __m128d Aw = _mm_mul_pd(vA, vw);
          _mm_storeu_pd(arg_ + n_, _mm_div_pd(_mm_add_pd(va, r), vay));
          _mm_storeu_pd(coef_ + n_,
                        _mm_mul_pd(Aw, _mm_add_pd(_mm_mul_pd(_mm_mul_pd(_mm_set1_pd(2.0), va), va),
                                                  _mm_mul_pd(vay, vay))));
          n_ += 2;
          double t[2];
          _mm_storeu_pd(t, _mm_mul_pd(_mm_mul_pd(Aw, va), r));
          rest_ -= t[0];
          rest_ -= t[1];
          k += 2;
          continue;
        }
      }
      const double ak = a[k];
      if (ak > 0.0 && ay0 < 6.0 * w) {
        const double yp = y0 + 0.5 * w, ym = y0 - 0.5 * w;
        if (yp != 0.0 && ym != 0.0) {  // both edges of a near strip
          const double factor = 2.0 * A[k];
          const __m128d f = _mm_set_pd(ym > 0.0 ? -factor : factor, yp > 0.0 ? factor : -factor);
          const __m128d vy = _mm_set_pd(ym, yp);
          const __m128d vay = _mm_andnot_pd(sign, vy);
          const __m128d va = _mm_set1_pd(ak);
          const __m128d r =
              _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(va, va), _mm_mul_pd(vay, vay)));
          const __m128d arg1 = _mm_div_pd(_mm_add_pd(vay, r), va);  // asinh(|y|/a)
          const __m128d arg2 = _mm_div_pd(_mm_add_pd(va, r), vay);  // asinh(a/|y|)
          const __m128d coef1 = _mm_mul_pd(f, _mm_set1_pd(2.0 * ak * ak * ak / 3.0));
          const __m128d coef2 = _mm_mul_pd(
              f, _mm_add_pd(_mm_mul_pd(_mm_mul_pd(va, va), vay),
                            _mm_div_pd(_mm_mul_pd(_mm_mul_pd(vay, vay), vay), _mm_set1_pd(6.0))));
          _mm_storeu_pd(arg_ + n_, _mm_unpacklo_pd(arg1, arg2));
          _mm_storeu_pd(arg_ + n_ + 2, _mm_unpackhi_pd(arg1, arg2));
          _mm_storeu_pd(coef_ + n_, _mm_unpacklo_pd(coef1, coef2));
          _mm_storeu_pd(coef_ + n_ + 2, _mm_unpackhi_pd(coef1, coef2));
          n_ += 4;
          double t[2];
          _mm_storeu_pd(
              t, _mm_mul_pd(f, _mm_div_pd(_mm_mul_pd(_mm_mul_pd(vay, va), r), _mm_set1_pd(6.0))));
          rest_ -= t[0];
          rest_ -= t[1];
          ++k;
          continue;
        }
      }
      add(A[k], ak, y0, w);
      ++k;
    }
#else
    for (int k = 0; k < n; ++k) add(A[k], a[k], s_lo + (k + 0.5) * width - s_ref, width);
#endif
  }

void BoussinesqSum::total2(const BoussinesqSum& s1, const BoussinesqSum& s2, double* t1,
                           double* t2) {
    double sum1 = s1.rest_, sum2 = s2.rest_;
    int i = 0;
#if defined(RAILTAB_STRIPES_AVX2)
    if (have_avx2()) {
      const int m4 = std::min(s1.n_, s2.n_) & ~3;
      log_sums_avx2(s1.arg_, s1.coef_, s2.arg_, s2.coef_, m4, &sum1, &sum2);
      i = m4;
    }
#endif
    const int m = std::min(s1.n_, s2.n_) & ~1;
#if defined(__SSE2__)
    for (; i < m; i += 2) {
      double u1[2], u2[2];
      _mm_storeu_pd(u1, _mm_mul_pd(fast_log_pd(_mm_loadu_pd(s1.arg_ + i)),
                                   _mm_loadu_pd(s1.coef_ + i)));
      _mm_storeu_pd(u2, _mm_mul_pd(fast_log_pd(_mm_loadu_pd(s2.arg_ + i)),
                                   _mm_loadu_pd(s2.coef_ + i)));
      sum1 += u1[0];
      sum2 += u2[0];
      sum1 += u1[1];
      sum2 += u2[1];
    }
#endif
    *t1 = s1.sum_from(i, sum1);
    *t2 = s2.sum_from(i, sum2);
  }

double BoussinesqSum::sum_from(int i, double sum) const {
#if defined(__SSE2__)
    for (; i + 1 < n_; i += 2) {
      const __m128d l = fast_log_pd(_mm_loadu_pd(arg_ + i));
      const __m128d c = _mm_loadu_pd(coef_ + i);
      double t[2];
      _mm_storeu_pd(t, _mm_mul_pd(l, c));
      sum += t[0];
      sum += t[1];
    }
#endif
    for (; i < n_; ++i) sum += coef_[i] * fast_log(arg_[i]);
    return sum;
  }

}  // namespace railtab::detail
