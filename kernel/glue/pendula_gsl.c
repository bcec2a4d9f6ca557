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

/* ------------------------------------------------------------------ */
/* GSL odeiv2 with the rk8pd stepper on pendula's own right-hand side. */

#include <gsl/gsl_odeiv2.h>

double pendula_accel_c(const double *params, double t, double th, double v);

struct pendula_sys { const double *params; long nfev; };

static int pendula_gsl_rhs(double t, const double y[], double f[], void *p) {
  struct pendula_sys *s = (struct pendula_sys *)p;
  f[0] = y[1];
  f[1] = pendula_accel_c(s->params, t, y[0], y[1]);
  s->nfev++;
  return GSL_SUCCESS;
}

/* Integrate from t = 0 through the ascending times tout (all >= 0).
 * Returns 0, or the GSL status of the failure (outputs after it are NaN).
 * stats: [steps, rhs evaluations]. */
int pendula_gsl_rk8pd(const double *params, double theta0, double v0, int n, const double *tout,
                      double rtol, double atol, double *theta, double *v, double *stats) {
  struct pendula_sys s = {params, 0};
  gsl_odeiv2_system sys = {pendula_gsl_rhs, NULL, 2, &s};
  gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_standard_new(&sys, gsl_odeiv2_step_rk8pd,
                                                              1e-6, atol, rtol, 1.0, 0.0);
  if (d == NULL) return GSL_ENOMEM;
  double t = 0.0, y[2] = {theta0, v0};
  int status = GSL_SUCCESS;
  for (int i = 0; i < n; ++i) {
    if (status == GSL_SUCCESS && tout[i] != t) status = gsl_odeiv2_driver_apply(d, &t, tout[i], y);
    theta[i] = status == GSL_SUCCESS ? y[0] : NAN;
    v[i] = status == GSL_SUCCESS ? y[1] : NAN;
  }
  stats[0] = (double)d->e->count;
  stats[1] = (double)s.nfev;
  gsl_odeiv2_driver_free(d);
  return status;
}
