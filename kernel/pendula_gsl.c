/* GSL glue for pendula: the peers that benchmarks and checks compare with.
 *
 * GSL's default error handler calls abort(), even from the _e functions, so
 * pendula_gsl_init() switches it off; every call here checks the status
 * and reports failures as NaN plus a count, never by aborting.
 */
#include <math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_elljac.h>
#include <gsl/gsl_sf_ellint.h>

void pendula_gsl_init(void) { gsl_set_error_handler_off(); }

/* sn, cn, dn(u|m) by GSL (Bulirsch's algorithm); returns the number of failures. */
int pendula_gsl_elljac(int n, const double *u, const double *m,
                       double *sn, double *cn, double *dn) {
  int bad = 0;
  for (int i = 0; i < n; ++i) {
    if (gsl_sf_elljac_e(u[i], m[i], &sn[i], &cn[i], &dn[i]) != GSL_SUCCESS) {
      sn[i] = cn[i] = dn[i] = NAN;
      ++bad;
    }
  }
  return bad;
}

/* K(m) by GSL's Carlson R_F (takes the modulus k = sqrt(m)). */
int pendula_gsl_kcomp(int n, const double *m, double *k) {
  int bad = 0;
  gsl_sf_result r;
  for (int i = 0; i < n; ++i) {
    if (m[i] < 0.0 || gsl_sf_ellint_Kcomp_e(sqrt(m[i]), GSL_PREC_DOUBLE, &r) != GSL_SUCCESS) {
      k[i] = NAN;
      ++bad;
    } else {
      k[i] = r.val;
    }
  }
  return bad;
}
