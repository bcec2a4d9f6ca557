/* GSL's one-dimensional root finder and QAWS quadrature on a function given
 * by the Fortran caller (a bind(C) function of x and an opaque context), for
 * the exact energy balance of dry friction (kernel/models/pendula_friction.f90)
 * and the release of a stuck bob (kernel/dispatch/pendula_stick_slip.f90). */
#include <math.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_integration.h>

typedef double (*pendula_fn)(double x, void *ctx);

struct pendula_fn_ctx { pendula_fn f; void *ctx; };

static double pendula_call(double x, void *p) {
  struct pendula_fn_ctx *c = (struct pendula_fn_ctx *)p;
  return c->f(x, c->ctx);
}

/* A root of f in [lo, hi] (f(lo), f(hi) of opposite signs or zero) by Brent's
 * method, to the interval width xtol + 4 DBL_EPSILON |x|.  Returns 0, or 1
 * (no sign change), 2 (no convergence in maxit), 3 (GSL failed). */
int pendula_gsl_root(pendula_fn f, void *ctx, double lo, double hi, double xtol, int maxit, double *root) {
  struct pendula_fn_ctx c = {f, ctx};
  double flo = f(lo, ctx), fhi = f(hi, ctx);
  if (flo == 0.0) { *root = lo; return 0; }
  if (fhi == 0.0) { *root = hi; return 0; }
  if ((flo > 0) == (fhi > 0) || !isfinite(flo) || !isfinite(fhi)) return 1;
  gsl_function F = {pendula_call, &c};
  gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (s == NULL) return 3;
  if (gsl_root_fsolver_set(s, &F, lo, hi) != GSL_SUCCESS) { gsl_root_fsolver_free(s); return 3; }
  int result = 2;
  for (int it = 0; it < maxit; ++it) {
    if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) { result = 3; break; }
    double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
    if (gsl_root_test_interval(a, b, xtol, 4.0 * DBL_EPSILON) == GSL_SUCCESS || a == b) { result = 0; break; }
  }
  *root = gsl_root_fsolver_root(s);
  gsl_root_fsolver_free(s);
  return result;
}

/* The integral over [a, b] of f(x) (x - a)^alpha (b - x)^beta (alpha, beta > -1)
 * by GSL's QAWS, to the relative error epsrel.  Returns 0 or GSL's status. */
int pendula_gsl_qaws(pendula_fn f, void *ctx, double a, double b, double alpha, double beta, double epsrel,
                     double *result, double *abserr) {
  struct pendula_fn_ctx c = {f, ctx};
  gsl_function F = {pendula_call, &c};
  gsl_integration_qaws_table *t = gsl_integration_qaws_table_alloc(alpha, beta, 0, 0);
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  if (t == NULL || w == NULL) {
    if (t) gsl_integration_qaws_table_free(t);
    if (w) gsl_integration_workspace_free(w);
    return GSL_ENOMEM;
  }
  int st = gsl_integration_qaws(&F, a, b, t, 0.0, epsrel, 1000, w, result, abserr);
  gsl_integration_qaws_table_free(t);
  gsl_integration_workspace_free(w);
  return st;
}
