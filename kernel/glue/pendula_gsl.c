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
#include <gsl/gsl_sf_mathieu.h>

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

/* GSL's Mathieu characteristic value a_n(q) (kind 1) or b_n(q) (kind 2) of
 * integer order n, one value per call of gsl_sf_mathieu_a_e/_b_e (Alhargan's
 * algorithm); returns the number of failures (NaN there). */
int pendula_gsl_mathieu(int kind, int n, const int *order, const double *q, double *val) {
  int bad = 0;
  gsl_sf_result r;
  for (int i = 0; i < n; ++i) {
    int st = kind == 1 ? gsl_sf_mathieu_a_e(order[i], q[i], &r) : gsl_sf_mathieu_b_e(order[i], q[i], &r);
    if (st != GSL_SUCCESS) {
      val[i] = NAN;
      ++bad;
    } else {
      val[i] = r.val;
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
/* The flow with its monodromy: the one core of the periodic orbits and  */
/* their continuation (python/pendula/dynamics/periodic.py).             */

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

/* How often the cancel flag is read (steps). */
#define PENDULA_CANCEL_POLL 256

/* The flow from (theta0, v0) at t = 0 through the times tout[0 .. nt-1] (all of
 * one sign, in order away from 0: forward or backward in time), with the
 * monodromy mono = [[dtheta/dtheta0, dtheta/dv0], [dv/dtheta0, dv/dv0]] (row
 * major, 4 numbers a time) and the right-hand side (theta', v') at each time.
 * rk8pd with GSL's standard step control, stepped here so that the cancel flag
 * is read every PENDULA_CANCEL_POLL steps and at most nmax steps are taken.
 * Returns 0, 1 (the integrator failed or the state left the finite numbers),
 * 2 (more than nmax steps: the work limit), 3 (cancelled). */
int pendula_gsl_flow_monodromy(const void *model, double theta0, double v0, int nt, const double *tout,
                               double rtol, double atol, long nmax, const volatile int *cancel,
                               double *ends, double *monos, double *fend, double *nfev) {
  struct pendula_sys s = {model, 0};
  gsl_odeiv2_system sys = {pendula_variational_rhs, NULL, 6, &s};
  gsl_odeiv2_step *st = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 6);
  gsl_odeiv2_control *c = gsl_odeiv2_control_standard_new(atol, rtol, 1.0, 0.0);
  gsl_odeiv2_evolve *e = gsl_odeiv2_evolve_alloc(6);
  int status = 0;
  if (st == NULL || c == NULL || e == NULL) status = 1;
  double t = 0.0, y[6] = {theta0, v0, 1.0, 0.0, 0.0, 1.0}, f[6];
  double h = (nt > 0 && tout[nt - 1] < 0.0) ? -1e-3 : 1e-3;
  long steps = 0;
  for (int i = 0; i < nt && status == 0; ++i) {
    while (t != tout[i]) {
      if (steps >= nmax) { status = 2; break; }
      if (steps % PENDULA_CANCEL_POLL == 0 && *cancel != 0) { status = 3; break; }
      if (gsl_odeiv2_evolve_apply(e, c, st, &sys, &t, tout[i], &h, y) != GSL_SUCCESS) { status = 1; break; }
      ++steps;
      if (!(isfinite(y[0]) && isfinite(y[1]) && isfinite(y[2]) && isfinite(y[3]) && isfinite(y[4]) &&
            isfinite(y[5]))) { status = 1; break; }
    }
    if (status != 0) break;
    pendula_variational_rhs(t, y, f, &s);
    ends[2 * i] = y[0];
    ends[2 * i + 1] = y[1];
    monos[4 * i] = y[2]; monos[4 * i + 1] = y[4];
    monos[4 * i + 2] = y[3]; monos[4 * i + 3] = y[5];
    fend[2 * i] = f[0];
    fend[2 * i + 1] = f[1];
  }
  if (e != NULL) gsl_odeiv2_evolve_free(e);
  if (c != NULL) gsl_odeiv2_control_free(c);
  if (st != NULL) gsl_odeiv2_step_free(st);
  *nfev = (double)s.nfev;
  return status;
}

/* ------------------------------------------------------------------ */
/* Newton inside the kernel: the attractor finder's confirmation of a   */
/* recurring cycle (kernel/sweep/pendula_attractors.f90), on OpenMP     */
/* threads where Python's Newton (dynamics/periodic.py) cannot run.     */
/* The flow and monodromy are the one core above.                       */

#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_vector.h>
#include <gsl/gsl_matrix.h>

struct pendula_po { const void *model; double T, shift, rtol, atol, nfev; };

/* The flow over [0, T] with its monodromy, within the work limit of the
 * dynamics (max(1e6, 1000 T) steps); not cancellable (a few periods). */
static int pendula_po_flow(struct pendula_po *po, double th, double v, double *end, double *mono) {
  static const volatile int no_cancel = 0;
  double fend[2], nfev = 0.0;
  long nmax = (long)fmax(1e6, fmin(1e12, 1000.0 * fabs(po->T)));
  int st = pendula_gsl_flow_monodromy(po->model, th, v, 1, &po->T, po->rtol, po->atol, nmax, &no_cancel,
                                      end, mono, fend, &nfev);
  po->nfev += nfev;
  return st == 0 ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* F(x) = P(x) - x - (2 pi winding, 0) and its Jacobian M - I. */
static int pendula_po_fdf(const gsl_vector *x, void *p, gsl_vector *f, gsl_matrix *J) {
  struct pendula_po *po = (struct pendula_po *)p;
  double end[2], mono[4];
  if (pendula_po_flow(po, gsl_vector_get(x, 0), gsl_vector_get(x, 1), end, mono) != GSL_SUCCESS)
    return GSL_EBADFUNC;
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
 * Returns 0, 1 (no convergence in maxit), 2 (the flow failed: non-finite, the
 * integrator's error or the work limit), 3 (the iteration stalled). */
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
    if (pendula_po_flow(&po, x[0], x[1], end, mono) != GSL_SUCCESS)
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
