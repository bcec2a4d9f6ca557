/* GSL's a_n(q) of the points in a file (argument 1), argument 2 times, one gsl_sf_mathieu_a_e call a value. */
#include <stdio.h>
#include <stdlib.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_mathieu.h>
int main(int argc, char **argv) {
  FILE *f = fopen(argv[1], "r"); int reps = atoi(argv[2]); int n; fscanf(f, "%d", &n);
  int *o = malloc(n * sizeof(int)); double *q = malloc(n * sizeof(double));
  for (int i = 0; i < n; ++i) fscanf(f, "%d %lf", &o[i], &q[i]);
  gsl_set_error_handler_off(); double acc = 0; gsl_sf_result r;
  for (int k = 0; k < reps; ++k) for (int i = 0; i < n; ++i) if (gsl_sf_mathieu_a_e(o[i], q[i], &r) == GSL_SUCCESS) acc += r.val;
  printf("%g\n", acc); return 0;
}
