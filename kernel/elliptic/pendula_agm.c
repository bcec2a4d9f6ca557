/* K(m) = pi / (2 AGM(1, sqrt(mc))) in double-double for arrays of parameters:
 * the per-element path of the Jacobi functions (jacobi_eval_varm), where this
 * AGM was a third of the time.
 *
 * Why C: a double-double AGM is made of exact products a b = p + e, and with a
 * fused multiply-add e = fma(a, b, -p) is 2 operations instead of Dekker's 17.
 * gfortran 12 can only fuse by contracting every a*b + c (which would break
 * the error-free transformations everywhere else: the kernel is built with
 * -ffp-contract=off); C has fma() itself.  The function is compiled twice:
 * for CPUs with AVX2 and FMA (a target attribute; fma() becomes one
 * instruction and the loop runs 4 doubles a vector) and portably, with
 * Dekker's product; the caller's CPU picks one at run time.  Both give the
 * same K up to the last bits of its low part (the two exact products agree
 * exactly; only the order of the roundings of the low parts differs).
 *
 * For 2^-60 <= mc <= 1 (the caller sends smaller mc to the expansion about
 * m = 1): the AGM of (1, sqrt(mc)) two steps for all, then the few pairs with
 * |a - b| > 2^-7 (a + b) (3 % of uniform m; ~6 steps for mc near 2^-60) one by
 * one, closed by M = A - c^2/(4A) - A t^4 (5/64 + 11 t^2/256 + 469 t^4/16384)
 * with A = (a + b)/2, c = (a - b)/2, t = c/A <= 2^-7: c^2/(4A) (2^-16 of A) in
 * double-double, the rest (below 2^-31 of A) in double; the first term left
 * out, 1379/65536 t^10, is below 2^-75 of A.  K to ~2^-75 relative is what
 * the reduction of u over 1e4 periods needs (tests/test_reference_grids.py).
 * Also returned: sqrt(mc) (smc), which the Jacobi block needs anyway.
 */
#include <math.h>

/* The build gives C -fno-math-errno (meson.build): sqrt without the errno
   path, so that the loops vectorize (sqrt of a negative number cannot occur
   here: every argument is mc >= 0 or a product of positive AGM terms). */


#define PI_HI 3.141592653589793116
#define PI_LO 1.2246467991473532e-16

/* one double-double AGM step on (a, b), and the whole computation, written
   once as a macro body over a product macro TWO_PROD(x, y, p, e) */
#define AGM_STEP(a, al, b, bl)                                                \
  do {                                                                        \
    double sm_ = a + b, t_ = sm_ - a;                                         \
    double e_ = (a - (sm_ - t_)) + (b - t_) + (al + bl);                      \
    double an_ = sm_ + e_, anl_ = e_ - (an_ - sm_);                           \
    double p_, pe_;                                                           \
    TWO_PROD(a, b, p_, pe_);                                                  \
    pe_ += a * bl + al * b;                                                   \
    sm_ = p_ + pe_; pe_ = pe_ - (sm_ - p_); p_ = sm_;                         \
    double r_ = sqrt(p_), q_, qe_;                                            \
    TWO_PROD(r_, r_, q_, qe_);                                                \
    double c_ = (((p_ - q_) - qe_) + pe_) / (2.0 * r_);                       \
    b = r_ + c_; bl = c_ - (b - r_);                                          \
    a = 0.5 * an_; al = 0.5 * anl_;                                           \
  } while (0)

#define AGM_K_BODY                                                            \
  enum { BLK = 256 };                                                         \
  double a[BLK], al[BLK], b[BLK], bl[BLK];                                    \
  for (int i0 = 0; i0 < n; i0 += BLK) {                                       \
    int nb = n - i0 < BLK ? n - i0 : BLK;                                     \
    const double *mcb = mc + i0, *mclb = mcl + i0;                            \
    double *khb = kh + i0, *klb = kl + i0, *smcb = smc + i0;                  \
    for (int i = 0; i < nb; ++i) {                                            \
      double x = sqrt(mcb[i]), p, pe;                                         \
      smcb[i] = x;                                                            \
      TWO_PROD(x, x, p, pe);                                                  \
      a[i] = 1.0; al[i] = 0.0;                                                \
      b[i] = x; bl[i] = (((mcb[i] - p) - pe) + mclb[i]) / (2.0 * x);          \
    }                                                                         \
    for (int i = 0; i < nb; ++i) {                                            \
      double ai = a[i], ali = al[i], bi = b[i], bli = bl[i];                  \
      AGM_STEP(ai, ali, bi, bli);                                             \
      AGM_STEP(ai, ali, bi, bli);                                             \
      a[i] = ai; al[i] = ali; b[i] = bi; bl[i] = bli;                         \
    }                                                                         \
    for (int i = 0; i < nb; ++i) {                                            \
      double ai = a[i], ali = al[i], bi = b[i], bli = bl[i];                  \
      for (int it = 0; it < 64 && fabs(ai - bi) > 0.0078125 * (ai + bi); ++it) \
        AGM_STEP(ai, ali, bi, bli);                                           \
      a[i] = ai; al[i] = ali; b[i] = bi; bl[i] = bli;                         \
    }                                                                         \
    for (int i = 0; i < nb; ++i) {                                            \
      double ai = a[i], ali = al[i], bi = b[i], bli = bl[i];                  \
      double sm = ai + bi, t = sm - ai;                                       \
      double e = (ai - (sm - t)) + (bi - t) + (ali + bli);                    \
      double h2 = 0.5 * (sm + e), l2 = 0.5 * (e - ((sm + e) - sm));           \
      double x = 0.5 * (ai - bi), y = 0.5 * (ali - bli);                      \
      double cc = x + y, cl = y - (cc - x);                                   \
      double p, pe;                                                           \
      TWO_PROD(cc, cc, p, pe);                                                \
      pe += 2.0 * cc * cl;                                                    \
      double r = 0.25 / h2, qq = p * r, q4 = 4.0 * h2, qp, qe;                \
      TWO_PROD(qq, q4, qp, qe);                                               \
      double ql = (((p - qp) - qe) + pe - qq * 4.0 * l2) * r;                 \
      double tt = cc / h2;                                                    \
      tt = tt * tt;                                                           \
      double corr = h2 * tt * tt * (5.0 / 64.0 + tt * (11.0 / 256.0           \
                    + tt * (469.0 / 16384.0)));                               \
      double mh = h2 - qq;                                                    \
      double ml = (((h2 - mh) - qq) + l2) - (ql + corr);                      \
      sm = mh + ml; ml = ml - (sm - mh); mh = sm;                             \
      /* K = pi / (2 M) */                                                    \
      double m2 = 2.0 * mh, q = PI_HI / m2, pp, ppe;                          \
      TWO_PROD(m2, q, pp, ppe);                                               \
      double rr = ((PI_HI - pp) - ppe) + (PI_LO - 2.0 * ml * q);              \
      double kq = q + rr / m2;                                                \
      khb[i] = kq;                                                            \
      klb[i] = rr / m2 - (kq - q);                                            \
    }                                                                         \
  }

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define HAVE_FMA_CLONE 1
#define TWO_PROD(x, y, p, e) do { p = (x) * (y); e = fma((x), (y), -p); } while (0)
__attribute__((target("avx2,fma")))
static void agm_k_fma(int n, const double *restrict mc, const double *restrict mcl,
                      double *restrict kh, double *restrict kl, double *restrict smc) {
  AGM_K_BODY
}
#undef TWO_PROD
#endif

/* Dekker's exact product (needs -ffp-contract=off, which the build sets) */
#define TWO_PROD(x, y, p, e)                                                  \
  do {                                                                        \
    double x_ = (x), y_ = (y), s_;                                            \
    p = x_ * y_;                                                              \
    s_ = 134217729.0 * x_; double xh_ = s_ - (s_ - x_), xl_ = x_ - xh_;        \
    s_ = 134217729.0 * y_; double yh_ = s_ - (s_ - y_), yl_ = y_ - yh_;        \
    e = ((xh_ * yh_ - p) + xh_ * yl_ + xl_ * yh_) + xl_ * yl_;                \
  } while (0)

static void agm_k_generic(int n, const double *restrict mc, const double *restrict mcl,
                          double *restrict kh, double *restrict kl, double *restrict smc) {
  AGM_K_BODY
}
#undef TWO_PROD

void pendula_agm_k(int n, const double *mc, const double *mcl, double *kh, double *kl, double *smc) {
#ifdef HAVE_FMA_CLONE
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    agm_k_fma(n, mc, mcl, kh, kl, smc);
    return;
  }
#endif
  agm_k_generic(n, mc, mcl, kh, kl, smc);
}
