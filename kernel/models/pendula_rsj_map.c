/* The overdamped (RSJ) Josephson junction under an rf drive: its stroboscopic
 * map and its rotation number (the mean voltage).
 *
 * In units of the characteristic frequency omega_c = 2 pi I_c R / Phi_0 the
 * phase obeys the first-order equation
 *
 *     phi' = i + a cos(Omega t) - sin(phi),
 *
 * i = I / I_c, a = I_rf / I_c.  Its stroboscopic map over one drive period
 * T = 2 pi / Omega, F(x) = phi(T; phi(0) = x), is the lift of an increasing
 * circle map: F(x + 2 pi) = F(x) + 2 pi, so g(x) = F(x) - x is 2 pi-periodic
 * and its oscillation is below 2 pi.  The rotation number rho (cycles per
 * period; <phi'> = rho Omega) is the integer n exactly when g(x) = 2 pi n has
 * a root, that is when min g <= 2 pi n <= max g (a fixed point of the map
 * advanced by n turns: the phase is locked on the n-th Shapiro step); else
 * it lies strictly between two integers, and (F^K(x) - x) / (2 pi K) is
 * within 1 / K of it for every x (Herman; the lift of an increasing circle
 * map).
 *
 * F by GSL's odeiv2 rk8pd (Prince-Dormand 8(7)) with the standard step
 * control; the extrema of g by GSL's Brent minimizer from the best of 32
 * samples.  No state outside the arguments (OpenMP-safe); GSL's error
 * handler is off (pendula_gsl_init): every status is checked.
 */
#include <math.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_odeiv2.h>

#define RSJ_SAMPLES 32
#define RSJ_TWO_PI 6.283185307179586476925286766559

struct rsj_par { double i, a, omega; };

struct rsj_map {
  struct rsj_par p;
  double period, rtol, atol;
  long nfev;
  int status;                 /* 0, or 1 once an integration has failed */
};

static int rsj_rhs(double t, const double y[], double f[], void *params) {
  const struct rsj_par *p = (const struct rsj_par *)params;
  f[0] = p->i + p->a * cos(p->omega * t) - sin(y[0]);
  return GSL_SUCCESS;
}

/* phi after n periods from phi(0) = x; NaN and status 1 on a failure. */
static double rsj_flow(struct rsj_map *m, double x, long n) {
  struct rsj_par par = m->p;
  gsl_odeiv2_system sys = {rsj_rhs, NULL, 1, &par};
  gsl_odeiv2_step *st = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 1);
  gsl_odeiv2_control *c = gsl_odeiv2_control_standard_new(m->atol, m->rtol, 1.0, 0.0);
  gsl_odeiv2_evolve *e = gsl_odeiv2_evolve_alloc(1);
  double y[1] = {x}, t = 0.0, h = m->period / 64.0, turns = 0.0;
  int ok = st != NULL && c != NULL && e != NULL;
  for (long k = 0; ok && k < n; ++k) {
    /* each period from t = 0 (the drive is periodic): no loss of the time's digits over long runs */
    t = 0.0;
    while (ok && t < m->period) {
      if (gsl_odeiv2_evolve_apply(e, c, st, &sys, &t, m->period, &h, y) != GSL_SUCCESS || !isfinite(y[0]))
        ok = 0;
    }
    /* keep phi in [0, 2 pi) and count the whole turns apart, exactly */
    double w = floor(y[0] / RSJ_TWO_PI);
    turns += w;
    y[0] -= w * RSJ_TWO_PI;
  }
  if (e != NULL) { m->nfev += 13 * (long)e->count; gsl_odeiv2_evolve_free(e); }
  if (c != NULL) gsl_odeiv2_control_free(c);
  if (st != NULL) gsl_odeiv2_step_free(st);
  if (!ok) { m->status = 1; return NAN; }
  return y[0] + turns * RSJ_TWO_PI;
}

static double rsj_gap(double x, void *params) {       /* g(x) = F(x) - x */
  struct rsj_map *m = (struct rsj_map *)params;
  return rsj_flow(m, x, 1) - x;
}

static double rsj_neg_gap(double x, void *params) { return -rsj_gap(x, params); }

/* The extremum of g near the sample k (sign +1: the minimum, -1: the maximum) by Brent. */
static double rsj_extremum(struct rsj_map *m, const double *gs, int k, double sign) {
  double h = RSJ_TWO_PI / RSJ_SAMPLES, x = k * h, best = sign * gs[k];
  gsl_function f = {sign > 0 ? rsj_gap : rsj_neg_gap, m};
  double lo = x - h, hi = x + h, flo = sign * gs[(k + RSJ_SAMPLES - 1) % RSJ_SAMPLES];
  double fhi = sign * gs[(k + 1) % RSJ_SAMPLES];
  if (!(best < flo && best < fhi)) return sign * best;          /* flat to rounding: the sample is the extremum */
  gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (s == NULL) { m->status = 1; return NAN; }
  if (gsl_min_fminimizer_set_with_values(s, &f, x, best, lo, flo, hi, fhi) == GSL_SUCCESS) {
    for (int it = 0; it < 100 && m->status == 0; ++it) {
      if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) break;
      double a = gsl_min_fminimizer_x_lower(s), b = gsl_min_fminimizer_x_upper(s);
      if (gsl_min_test_interval(a, b, 1e-9, 0.0) == GSL_SUCCESS) break;
    }
    double fm = gsl_min_fminimizer_f_minimum(s);
    if (fm < best) best = fm;
  }
  gsl_min_fminimizer_free(s);
  return sign * best;
}

/* The range [gmin, gmax] of g = F(x) - x over x (its extrema), for the step edges. */
int pendula_rsj_gap_range(double i, double a, double omega, double rtol, double atol,
                          double *gmin, double *gmax, double *nfev) {
  struct rsj_map m = {{i, a, omega}, RSJ_TWO_PI / omega, rtol, atol, 0, 0};
  double gs[RSJ_SAMPLES];
  int kmin = 0, kmax = 0;
  for (int k = 0; k < RSJ_SAMPLES; ++k) {
    gs[k] = rsj_gap(k * RSJ_TWO_PI / RSJ_SAMPLES, &m);
    if (gs[k] < gs[kmin]) kmin = k;
    if (gs[k] > gs[kmax]) kmax = k;
  }
  *gmin = *gmax = NAN;
  if (m.status == 0) {
    *gmin = rsj_extremum(&m, gs, kmin, 1.0);
    *gmax = rsj_extremum(&m, gs, kmax, -1.0);
  }
  *nfev = (double)m.nfev;
  return m.status;
}

/* The rotation number: rho (cycles per drive period), its error bound err
 * (0 when locked), the step n (locked) or NaN; status 0 decided, 6 locked,
 * 1 the integration failed (rho NaN).  periods: K of the estimate off the
 * steps (err = 1 / K). */
int pendula_rsj_rotation(double i, double a, double omega, double rtol, double atol, long periods,
                         double *rho, double *err, double *step, double *nfev) {
  double gmin, gmax;
  int st = pendula_rsj_gap_range(i, a, omega, rtol, atol, &gmin, &gmax, nfev);
  *rho = *err = *step = NAN;
  if (st != 0) return 1;
  double nlo = ceil(gmin / RSJ_TWO_PI), nhi = floor(gmax / RSJ_TWO_PI);
  if (nlo <= nhi) {                        /* 2 pi n in [gmin, gmax]: a fixed point n turns on */
    *rho = nlo + 0.0;                    /* + 0.0: the step 0 is +0, not -0 */
    *err = 0.0;
    *step = nlo + 0.0;
    return 6;
  }
  struct rsj_map m = {{i, a, omega}, RSJ_TWO_PI / omega, rtol, atol, 0, 0};
  double end = rsj_flow(&m, 0.0, periods);
  *nfev += (double)m.nfev;
  if (m.status != 0) return 1;
  double r = end / (RSJ_TWO_PI * (double)periods);
  /* rho lies strictly between the integers nhi and nlo: clip the estimate into that interval */
  if (r < nhi) r = nhi;
  if (r > nlo) r = nlo;
  *rho = r;
  *err = 1.0 / (double)periods;
  return 0;
}
