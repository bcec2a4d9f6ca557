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

/* The model's theta'' (kernel/glue/pendula_capi.f90); model is the opaque
 * address of a Fortran pendulum_model, owned by the caller. */
double pendula_accel_c(const void *model, double t, double th, double v);

struct pendula_sys { const void *model; long nfev; };

static int pendula_gsl_rhs(double t, const double y[], double f[], void *p) {
  struct pendula_sys *s = (struct pendula_sys *)p;
  f[0] = y[1];
  f[1] = pendula_accel_c(s->model, t, y[0], y[1]);
  s->nfev++;
  return GSL_SUCCESS;
}

/* Integrate from t = 0 through the ascending times tout (all >= 0).
 * Returns 0, or the GSL status of the failure (outputs after it are NaN).
 * stats: [steps, rhs evaluations]. */
int pendula_gsl_rk8pd(const void *model, double theta0, double v0, int n, const double *tout,
                      double rtol, double atol, double *theta, double *v, double *stats) {
  struct pendula_sys s = {model, 0};
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

/* ------------------------------------------------------------------ */
/* Periodic orbits of the stroboscopic map: Newton on the monodromy.    */

#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_vector.h>
#include <gsl/gsl_matrix.h>

void pendula_accel_jac_c(const void *model, double t, double th, double v, double *dadth, double *dadv);

/* The orbit and its two tangent columns: y = (theta, v, w11, w21, w12, w22),
 * dw/dt = J w with J = [[0, 1], [da/dtheta, da/dv]]. */
static int pendula_variational_rhs(double t, const double y[], double f[], void *p) {
  struct pendula_sys *s = (struct pendula_sys *)p;
  double dth, dv;
  f[0] = y[1];
  f[1] = pendula_accel_c(s->model, t, y[0], y[1]);
  pendula_accel_jac_c(s->model, t, y[0], y[1], &dth, &dv);
  f[2] = y[3];
  f[3] = dth * y[2] + dv * y[3];
  f[4] = y[5];
  f[5] = dth * y[4] + dv * y[5];
  s->nfev++;
  return GSL_SUCCESS;
}

/* The flow over [0, T] from (theta0, v0) with its monodromy matrix
 * mono = [[dtheta/dtheta0, dtheta/dv0], [dv/dtheta0, dv/dv0]] (row major). */
int pendula_gsl_flow_monodromy(const void *model, double theta0, double v0, double T,
                               double rtol, double atol, double *end, double *mono, double *nfev) {
  struct pendula_sys s = {model, 0};
  gsl_odeiv2_system sys = {pendula_variational_rhs, NULL, 6, &s};
  gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_standard_new(&sys, gsl_odeiv2_step_rk8pd,
                                                              1e-3, atol, rtol, 1.0, 0.0);
  if (d == NULL) return GSL_ENOMEM;
  double t = 0.0, y[6] = {theta0, v0, 1.0, 0.0, 0.0, 1.0};
  int status = gsl_odeiv2_driver_apply(d, &t, T, y);
  gsl_odeiv2_driver_free(d);
  *nfev += (double)s.nfev;
  if (status != GSL_SUCCESS) return status;
  for (int i = 0; i < 6; ++i)
    if (!isfinite(y[i])) return GSL_EBADFUNC;
  end[0] = y[0];
  end[1] = y[1];
  mono[0] = y[2]; mono[1] = y[4];
  mono[2] = y[3]; mono[3] = y[5];
  return GSL_SUCCESS;
}

struct pendula_po { const void *model; double T, shift, rtol, atol, nfev; };

/* F(x) = P(x) - x - (2 pi winding, 0) and its Jacobian M - I. */
static int pendula_po_fdf(const gsl_vector *x, void *p, gsl_vector *f, gsl_matrix *J) {
  struct pendula_po *po = (struct pendula_po *)p;
  double end[2], mono[4];
  int st = pendula_gsl_flow_monodromy(po->model, gsl_vector_get(x, 0), gsl_vector_get(x, 1), po->T,
                                      po->rtol, po->atol, end, mono, &po->nfev);
  if (st != GSL_SUCCESS) return GSL_EBADFUNC;
  if (f != NULL) {
    gsl_vector_set(f, 0, end[0] - gsl_vector_get(x, 0) - po->shift);
    gsl_vector_set(f, 1, end[1] - gsl_vector_get(x, 1));
  }
  if (J != NULL) {
    gsl_matrix_set(J, 0, 0, mono[0] - 1.0);
    gsl_matrix_set(J, 0, 1, mono[1]);
    gsl_matrix_set(J, 1, 0, mono[2]);
    gsl_matrix_set(J, 1, 1, mono[3] - 1.0);
  }
  return GSL_SUCCESS;
}

static int pendula_po_f(const gsl_vector *x, void *p, gsl_vector *f) { return pendula_po_fdf(x, p, f, NULL); }
static int pendula_po_df(const gsl_vector *x, void *p, gsl_matrix *J) {
  gsl_vector *f = gsl_vector_alloc(2);
  int st = pendula_po_fdf(x, p, f, J);
  gsl_vector_free(f);
  return st;
}

/* A fixed point of the map over T (k drive periods) that advances theta by
 * 2 pi winding, by GSL's hybridsj (Powell's hybrid method with the exact
 * Jacobian M - I, a safeguarded Newton).  x: guess in, orbit out; mono: the
 * monodromy at the orbit; info = [iterations, rhs evaluations, residual].
 * Returns 0, 1 (no convergence in maxit), 2 (the flow failed: non-finite or
 * the integrator's error), 3 (the iteration stalled: GSL_ENOPROG). */
int pendula_gsl_periodic_orbit(const void *model, double T, double winding, double rtol, double atol,
                               double tol, int maxit, double *x, double *mono, double *info) {
  struct pendula_po po = {model, T, 6.283185307179586 * winding, rtol, atol, 0.0};
  gsl_multiroot_function_fdf fdf = {pendula_po_f, pendula_po_df, pendula_po_fdf, 2, &po};
  gsl_multiroot_fdfsolver *sv = gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_hybridsj, 2);
  if (sv == NULL) return 2;
  gsl_vector *x0 = gsl_vector_alloc(2);
  gsl_vector_set(x0, 0, x[0]);
  gsl_vector_set(x0, 1, x[1]);
  int result = 1, it = 0;
  if (gsl_multiroot_fdfsolver_set(sv, &fdf, x0) != GSL_SUCCESS) {
    result = 2;
  } else {
    for (it = 1; it <= maxit; ++it) {
      int st = gsl_multiroot_fdfsolver_iterate(sv);
      if (st == GSL_EBADFUNC) { result = 2; break; }
      if (st == GSL_ENOPROG || st == GSL_ENOPROGJ) {
        result = gsl_multiroot_test_residual(sv->f, tol) == GSL_SUCCESS ? 0 : 3;
        break;
      }
      if (st != GSL_SUCCESS) { result = 3; break; }
      if (gsl_multiroot_test_residual(sv->f, tol) == GSL_SUCCESS &&
          gsl_multiroot_test_delta(sv->dx, sv->x, tol, tol) == GSL_SUCCESS) { result = 0; break; }
    }
  }
  if (result != 2) {
    x[0] = gsl_vector_get(sv->x, 0);
    x[1] = gsl_vector_get(sv->x, 1);
    double end[2];
    if (pendula_gsl_flow_monodromy(model, x[0], x[1], T, rtol, atol, end, mono, &po.nfev) != GSL_SUCCESS)
      result = 2;
    info[2] = fmax(fabs(end[0] - x[0] - po.shift), fabs(end[1] - x[1]));
  } else {
    info[2] = NAN;
  }
  info[0] = (double)it;
  info[1] = po.nfev;
  gsl_vector_free(x0);
  gsl_multiroot_fdfsolver_free(sv);
  return result;
}
