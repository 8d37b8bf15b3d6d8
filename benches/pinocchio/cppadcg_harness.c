// Calls one function written by cppadcg.cpp 1,000 times on varying inputs (argv: the number
// of joints, the function's name), for callgrind's inclusive count per call.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
void rnea(const double *x, double *y);
void fk(const double *x, double *y);
void jacobian(const double *x, double *y);
int main(int argc, char **argv) {
  int n = atoi(argv[1]);
  const char *which = argv[2];
  double x[64], y[256], acc = 0;
  for (int c = 0; c < 1000; ++c) {
    for (int i = 0; i < 3 * n; ++i) x[i] = 0.3 * ((c * 7 + i * 13) % 17) - 2.4;
    if (!strcmp(which, "rnea")) rnea(x, y);
    else if (!strcmp(which, "fk")) fk(x, y);
    else if (!strcmp(which, "jacobian")) jacobian(x, y);
    acc += y[1];
  }
  printf("%g\n", acc);
  return 0;
}
