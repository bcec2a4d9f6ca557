/* The rows of the Mathieu polish (kernel/mathieu/pendula_mathieu.f90,
 * polish_res): for the rows i1..i2 of a Hill-matrix window, the residual
 * r_i = ((T - x) z)_i in double-double with the matrix's entries exact
 * ((nu + 2k)^2 by two-sum and an exact product, 1 +- q, the coupling
 * sqrt(2) q of a_2m's first row), summed into z'r, z'z and r'r.
 *
 * Why C: the residual is made of exact products a b = p + e, and with a
 * fused multiply-add e = fma(a, b, -p) is 2 operations instead of Dekker's
 * 17 (gfortran 12 can only fuse by contracting every a*b + c, which would
 * break the error-free transformations; the kernel is built with
 * -ffp-contract=off).  As in kernel/elliptic/pendula_agm.c the loop is
 * compiled twice, for CPUs with FMA (a target attribute) and portably with
 * Dekker's product, and the caller's CPU picks one at run time.  Both give
 * the same exact products; only the order of the roundings of the low parts
 * differs (a few units of 1e-32 of the residual).
 *
 * Indices as in Fortran: z[0] is row 1, the window's row i has order index
 * r = r0 + i - 1; fam 0 is the bi-infinite matrix of offset nu, fam 1..4 the
 * one-sided matrices of a_2m, a_2m+1, b_2m+1, b_2m+2 (base order 0, 1, 1, 2).
 */

#define TWO_SUM(a, b, s, e)                                                   \
  do {                                                                        \
    double a_ = (a), b_ = (b), bb_;                                           \
    s = a_ + b_;                                                              \
    bb_ = s - a_;                                                             \
    e = (a_ - (s - bb_)) + (b_ - bb_);                                        \
  } while (0)

/* (rh + rl) += (th + tl) to double-double accuracy */
#define ADD_DD(rh, rl, th, tl)                                                \
  do {                                                                        \
    double s2_, e2_;                                                          \
    TWO_SUM(rh, th, s2_, e2_);                                                \
    e2_ = e2_ + (rl + tl);                                                    \
    rh = s2_ + e2_;                                                           \
    rl = e2_ - (rh - s2_);                                                    \
  } while (0)

#define POLISH_BODY                                                           \
  {                                                                           \
    double num = 0.0, den = 0.0, rr = 0.0;                                    \
    double base = (fam == 1) ? 0.0 : ((fam == 2 || fam == 3) ? 1.0 : 2.0);   \
    for (int i = i1; i <= i2; i++) {                                          \
      int r = r0 + i - 1;                                                     \
      double sh, sl, dh, dl, uh, ul, rh, rl, th, tl, zi = z[i - 1];           \
      if (fam == 0) {                                                         \
        TWO_SUM(nu, 2.0 * (double)r, sh, sl);                                 \
      } else {                                                                \
        sh = base + 2.0 * (double)r;                                          \
        sl = 0.0;                                                             \
      }                                                                       \
      TWO_PROD(sh, sh, dh, dl);                                               \
      dl = dl + 2.0 * sh * sl;                                                \
      if (r == 0 && fam == 2) {                                               \
        TWO_SUM(1.0, q, dh, dl);                                              \
      } else if (r == 0 && fam == 3) {                                        \
        TWO_SUM(1.0, -q, dh, dl);                                             \
      }                                                                       \
      TWO_SUM(dh, -x, uh, ul);                                                \
      ul = ul + dl;                                                           \
      TWO_PROD(uh, zi, rh, rl);                                               \
      rl = rl + ul * zi;                                                      \
      double zl = (i > 1) ? z[i - 2] : 0.0;                                   \
      double zr = (i < n) ? z[i] : 0.0;                                       \
      if (fam == 1 && r == 0) {                                               \
        TWO_PROD(e0, zr, th, tl);                                             \
        tl = tl + e0l * zr;                                                   \
        ADD_DD(rh, rl, th, tl);                                               \
        TWO_PROD(aq, zl, th, tl);                                             \
      } else if (fam == 1 && r == 1) {                                        \
        TWO_PROD(e0, zl, th, tl);                                             \
        tl = tl + e0l * zl;                                                   \
        ADD_DD(rh, rl, th, tl);                                               \
        TWO_PROD(aq, zr, th, tl);                                             \
      } else {                                                                \
        double zh, zt;                                                        \
        TWO_SUM(zl, zr, zh, zt);                                              \
        TWO_PROD(aq, zh, th, tl);                                             \
        tl = tl + aq * zt;                                                    \
      }                                                                       \
      ADD_DD(rh, rl, th, tl);                                                 \
      double ri = rh + rl;                                                    \
      num = num + zi * ri;                                                    \
      rr = rr + ri * ri;                                                      \
      den = den + zi * zi;                                                    \
    }                                                                         \
    *num_out = num;                                                           \
    *den_out = den;                                                           \
    *rr_out = rr;                                                             \
  }

#define POLISH_ARGS                                                           \
  int fam, double nu, double q, double aq, double e0, double e0l, int r0,     \
      int n, int i1, int i2, double x, const double *restrict z,             \
      double *restrict num_out, double *restrict den_out,                     \
      double *restrict rr_out

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define HAVE_FMA_CLONE 1
#define TWO_PROD(a, b, p, e)                                                  \
  do {                                                                        \
    double a3_ = (a), b3_ = (b);                                              \
    p = a3_ * b3_;                                                            \
    e = __builtin_fma(a3_, b3_, -p);                                          \
  } while (0)
__attribute__((target("fma")))
static void polish_rows_fma(POLISH_ARGS) POLISH_BODY
#undef TWO_PROD
#endif

/* Dekker's exact product (needs -ffp-contract=off, which the build sets) */
#define TWO_PROD(a, b, p, e)                                                  \
  do {                                                                        \
    double x_ = (a), y_ = (b), s_;                                            \
    p = x_ * y_;                                                              \
    s_ = 134217729.0 * x_; double xh_ = s_ - (s_ - x_), xl_ = x_ - xh_;        \
    s_ = 134217729.0 * y_; double yh_ = s_ - (s_ - y_), yl_ = y_ - yh_;        \
    e = ((xh_ * yh_ - p) + xh_ * yl_ + xl_ * yh_) + xl_ * yl_;                \
  } while (0)
static void polish_rows_generic(POLISH_ARGS) POLISH_BODY
#undef TWO_PROD

void pendula_mathieu_polish_rows(POLISH_ARGS) {
#ifdef HAVE_FMA_CLONE
  if (__builtin_cpu_supports("fma")) {
    polish_rows_fma(fam, nu, q, aq, e0, e0l, r0, n, i1, i2, x, z, num_out, den_out, rr_out);
    return;
  }
#endif
  polish_rows_generic(fam, nu, q, aq, e0, e0l, r0, n, i1, i2, x, z, num_out, den_out, rr_out);
}
