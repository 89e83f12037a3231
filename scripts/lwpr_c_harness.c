/* Drives the reference LWPR C library (../shared/reference/lwpr-c, built by its build.sh) on a
 * sample file written by `osrl bench references` and prints one JSON object:
 *   {"nmse": [per output], "n_rfs": N, "update_us": µs, "predict_us": µs,
 *    "update_us_batch": µs, "predict_us_batch": µs, "updates": n, "tests": n}
 * Two timings, both means per call with clock_gettime(CLOCK_MONOTONIC): "update_us" and
 * "predict_us" time every lwpr_update and lwpr_predict call on its own (the clock's own cost,
 * 20-40 ns a pair, is in them); the "_batch" ones time the whole loop once: the training is run
 * a second time on a fresh model (the same samples: the same model, bit for bit) and the test
 * set predicted a second time, the predictions stored and compared after the clock stops.
 * nMSE per output (from the first pass): test MSE over the (population) variance of the test
 * targets; a test point without an active RF predicts 0 (the library's own behaviour).
 *
 * Sample file (text, whitespace separated, numbers in round-trip precision):
 *   lwpr-samples 1
 *   n_in n_out
 *   init_d init_alpha w_gen w_prune diag_only meta meta_rate penalty update_d
 *   init_lambda final_lambda tau_lambda init_s2 add_threshold cutoff
 *   norm_in[n_in] norm_out[n_out]
 *   n_train, then n_train rows of x[n_in] y[n_out] in update order (all epochs)
 *   n_test, then n_test rows of x[n_in] y[n_out]
 *
 * Build: gcc -O2 -I OUT/include lwpr_c_harness.c OUT/liblwpr.a -lm ; run: harness FILE */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "lwpr.h"

static FILE *in;
static const char *path;

static void fail(const char *what) {
  fprintf(stderr, "lwpr_c_harness: %s: %s\n", path, what);
  exit(2);
}

static double num(const char *what) {
  double v;
  if (fscanf(in, "%lf", &v) != 1) fail(what);
  return v;
}

static long count(const char *what) {
  double v = num(what);
  if (v < 0 || v > 1e8 || v != (double)(long)v) fail(what);
  return (long)v;
}

static double *rows(long n, int width, const char *what) {
  double *r = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1) * (size_t)width);
  if (!r) fail("out of memory");
  for (long i = 0; i < n * width; i++) r[i] = num(what);
  return r;
}

static double now_us(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}

/* The settings of the sample file, in its order. */
static double set[15], *norm_in, *norm_out;

static void init(LWPR_Model *m, int n_in, int n_out) {
  if (!lwpr_init_model(m, n_in, n_out, "harness")) fail("lwpr_init_model failed");
  lwpr_set_init_D_spherical(m, set[0]);
  lwpr_set_init_alpha(m, set[1]);
  m->w_gen = set[2];
  m->w_prune = set[3];
  m->diag_only = (int)set[4];
  m->meta = (int)set[5];
  m->meta_rate = set[6];
  m->penalty = set[7];
  m->update_D = (int)set[8];
  m->init_lambda = set[9];
  m->final_lambda = set[10];
  m->tau_lambda = set[11];
  m->init_S2 = set[12];
  m->add_threshold = set[13];
  for (int i = 0; i < n_in; i++) m->norm_in[i] = norm_in[i];
  for (int i = 0; i < n_out; i++) m->norm_out[i] = norm_out[i];
}

int main(int argc, char **argv) {
  char magic[32];
  LWPR_Model m, mb;
  if (argc != 2) {
    fprintf(stderr, "usage: lwpr_c_harness SAMPLE_FILE\n");
    return 2;
  }
  path = argv[1];
  in = fopen(path, "r");
  if (!in) fail("cannot open");
  if (fscanf(in, "%31s", magic) != 1 || strcmp(magic, "lwpr-samples") != 0 || num("version") != 1)
    fail("not an lwpr-samples 1 file");
  int n_in = (int)count("n_in"), n_out = (int)count("n_out");
  if (n_in < 1 || n_out < 1) fail("n_in and n_out must be at least 1");
  const char *names[15] = {"init_d", "init_alpha", "w_gen", "w_prune", "diag_only", "meta",
                           "meta_rate", "penalty", "update_d", "init_lambda", "final_lambda",
                           "tau_lambda", "init_s2", "add_threshold", "cutoff"};
  for (int i = 0; i < 15; i++) set[i] = num(names[i]);
  double cutoff = set[14];
  norm_in = rows(1, n_in, "norm_in");
  norm_out = rows(1, n_out, "norm_out");
  init(&m, n_in, n_out);
  int w = n_in + n_out;
  long n_train = count("n_train");
  double *train = rows(n_train, w, "training row");
  long n_test = count("n_test");
  double *test = rows(n_test, w, "test row");
  if (n_train < 1 || n_test < 1) fail("needs training and test rows");
  fclose(in);

  double *yp = malloc(sizeof(double) * n_out), t_up = 0, t_pr = 0;
  for (long i = 0; i < n_train; i++) {
    double *r = train + i * w, t0 = now_us();
    int ok = lwpr_update(&m, r, r + n_in, yp, NULL);
    t_up += now_us() - t0;
    if (!ok) fail("lwpr_update failed (out of memory)");
  }
  /* The same training timed as one loop, on a fresh model. */
  init(&mb, n_in, n_out);
  int all_ok = 1;
  double t_up_batch = now_us();
  for (long i = 0; i < n_train; i++) {
    double *r = train + i * w;
    all_ok &= lwpr_update(&mb, r, r + n_in, yp, NULL);
  }
  t_up_batch = now_us() - t_up_batch;
  if (!all_ok) fail("lwpr_update failed (out of memory)");
  lwpr_free_model(&mb);
  double *se = calloc(n_out, sizeof(double)), *mean = calloc(n_out, sizeof(double));
  double *var = calloc(n_out, sizeof(double));
  for (long i = 0; i < n_test; i++) {
    double *r = test + i * w, t0 = now_us();
    lwpr_predict(&m, r, cutoff, yp, NULL, NULL);
    t_pr += now_us() - t0;
    for (int o = 0; o < n_out; o++) {
      double e = yp[o] - r[n_in + o];
      se[o] += e * e;
      mean[o] += r[n_in + o] / n_test;
    }
  }
  /* The predictions timed as one loop, stored, and checked against the first pass after. */
  double *ys = malloc(sizeof(double) * (size_t)n_test * (size_t)n_out);
  if (!ys) fail("out of memory");
  double t_pr_batch = now_us();
  for (long i = 0; i < n_test; i++) lwpr_predict(&m, test + i * w, cutoff, ys + i * n_out, NULL, NULL);
  t_pr_batch = now_us() - t_pr_batch;
  double *se_b = calloc(n_out, sizeof(double));
  for (long i = 0; i < n_test; i++)
    for (int o = 0; o < n_out; o++) {
      double e = ys[i * n_out + o] - test[i * w + n_in + o];
      se_b[o] += e * e;
    }
  for (int o = 0; o < n_out; o++)
    if (se_b[o] != se[o]) fail("the predictions timed as one loop differ from the first pass");
  for (long i = 0; i < n_test; i++)
    for (int o = 0; o < n_out; o++) {
      double d = test[i * w + n_in + o] - mean[o];
      var[o] += d * d / n_test;
    }
  long rfs = 0;
  for (int o = 0; o < n_out; o++) rfs += m.sub[o].numRFS;
  printf("{\"nmse\": [");
  for (int o = 0; o < n_out; o++) printf("%s%.17g", o ? ", " : "", se[o] / n_test / var[o]);
  printf("], \"n_rfs\": %ld, \"update_us\": %.6f, \"predict_us\": %.6f, "
         "\"update_us_batch\": %.6f, \"predict_us_batch\": %.6f, \"updates\": %ld, "
         "\"tests\": %ld}\n", rfs, t_up / n_train, t_pr / n_test, t_up_batch / n_train,
         t_pr_batch / n_test, n_train, n_test);
  lwpr_free_model(&m);
  return 0;
}
