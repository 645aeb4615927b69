/* fogpipe bench transform: the B-spline wavelet transform against GSL 2.7, PyWavelets
 * and a memcpy of the same bytes, on the same data, in one run.
 *
 * For each size (256^2, 512^2, 1024^2) and basis: forward and inverse with 3 levels and
 * with the full decomposition, and one fused level (a 1-level forward: rows and columns
 * of the level in one streaming pass), one thread and two. Medians of repeated runs
 * after warm-up. GB/s counts one read and one write of the fogmap (2 * 4 * N^2 bytes).
 * References: GSL gsl_wavelet2d_nstransform_forward with gsl_wavelet_bspline 202
 * (double, full decomposition), PyWavelets wavedec2 bior2.2 level 3 on float32 (timed
 * inside /usr/bin/python3), memcpy of the fogmap. The summary line (1024^2, linear,
 * one thread): speedup_vs_gsl = GSL full / ours full forward, speedup_vs_pywt = pywt
 * 3 levels / ours 3-level forward, bandwidth_fraction = memcpy / one fused level, both
 * timed interleaved in one loop (time_fused_vs_memcpy). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_wavelet.h>
#include <gsl/gsl_wavelet2d.h>

#include "app/cli_options.h"
#include "bench/bench.h"
#include "transform/transform.h"

#define MAX_REPS 101

static const int sizes[3] = {256, 512, 1024};
static const transform_basis bases[3] = {TRANSFORM_HAAR, TRANSFORM_LINEAR, TRANSFORM_QUADRATIC};
static const char *const basis_names[3] = {"haar", "linear", "quadratic"};

static int reps_for(int n) { return n <= 256 ? 61 : n <= 512 ? 31 : 21; }

static void fill(float *f, int n) {
  uint64_t s = 12345;
  for (int y = 0; y < n; y++)
    for (int x = 0; x < n; x++) {
      s = s * 6364136223846793005ull + 1442695040888963407ull;
      f[(size_t)y * n + x] = (float)(1.0 + 0.5 * sin(0.05 * x + 0.03 * y) +
                                     0.25 * (double)(s >> 40) / (double)(1 << 24));
    }
}

typedef enum { FORWARD, INVERSE } direction;

/* median ms of transform runs; forward reads `in` and writes `out`, inverse the reverse */
static double time_transform(int n, int levels, transform_basis basis, int threads,
                             direction dir, const float *in, float *coef, float *out) {
  transform_plan *plan;
  fog_error err;
  if (!(plan = transform_plan_create(&(transform_desc){.width = n, .height = n, .levels = levels,
          .basis = basis, .threads = threads}, &err))) {
    fprintf(stderr, "fogpipe bench transform: %s\n", err.message);
    return NAN;
  }
  int reps = reps_for(n);
  double t[MAX_REPS];
  transform_forward(plan, in, coef);
  /* A new plan's worker is a new thread, which the kernel first runs beside its parent on
   * the same core, where every hand-off waits for a time slice: in some runs the
   * multi-level two-thread rows read slower than one thread. Running the plan for 20 ms
   * first lets the scheduler move it, as a pipeline running frame after frame would. */
  for (double t0 = app_clock_seconds(); threads > 1 && app_clock_seconds() - t0 < 0.02;)
    transform_forward(plan, in, coef);
  for (int r = -2; r < reps; r++) {
    double t0 = app_clock_seconds();
    if (dir == FORWARD)
      transform_forward(plan, in, coef);
    else
      transform_inverse(plan, coef, out);
    double dt = app_clock_seconds() - t0;
    if (r >= 0) t[r] = dt;
  }
  transform_plan_destroy(plan);
  return 1e3 * app_median(t, reps);
}

/* Keeps both cores busy with two-thread transforms for `seconds` before anything is
 * timed. Without it, the first two-thread rows of a run (256^2) measured 3-4x slower than
 * one thread, and the same sizes 1.6x faster once the process had run two threads for a
 * few tens of milliseconds: the virtual machine's second core wakes slowly, not the
 * worker (it spins between passes). */
static void warm_up_two_threads(const float *in, float *coef, double seconds) {
  transform_plan *plan;
  fog_error err;
  if (!(plan = transform_plan_create(&(transform_desc){.width = 512, .height = 512, .levels = 3,
          .threads = 2}, &err)))
    return;
  double t0 = app_clock_seconds();
  while (app_clock_seconds() - t0 < seconds) transform_forward(plan, in, coef);
  transform_plan_destroy(plan);
}

static double time_memcpy(int n, const float *in, float *out) {
  int reps = reps_for(n);
  double t[MAX_REPS];
  for (int r = -2; r < reps; r++) {
    double t0 = app_clock_seconds();
    memcpy(out, in, sizeof(float) * (size_t)n * n);
    __asm__ volatile("" ::"r"(out) : "memory");
    double dt = app_clock_seconds() - t0;
    if (r >= 0) t[r] = dt;
  }
  return 1e3 * app_median(t, reps);
}

/* The bandwidth figure's two timings, interleaved: one fused level (1-level forward,
 * linear, one thread) and a memcpy of the same bytes from the same input, alternating in
 * one loop so that a busy machine slows both alike; medians of 101 pairs after warm-up.
 * The asm barrier keeps the copy from being elided. */
static void time_fused_vs_memcpy(int n, const float *in, float *coef, float *out,
                                 double *fused_ms, double *copy_ms) {
  transform_plan *plan;
  fog_error err;
  *fused_ms = *copy_ms = NAN;
  if (!(plan = transform_plan_create(&(transform_desc){.width = n, .height = n, .levels = 1,
          .basis = TRANSFORM_LINEAR, .threads = 1}, &err))) {
    fprintf(stderr, "fogpipe bench transform: %s\n", err.message);
    return;
  }
  enum { PAIRS = 101 };
  double tf[PAIRS], tc[PAIRS];
  for (int r = -5; r < PAIRS; r++) {
    double t0 = app_clock_seconds();
    transform_forward(plan, in, coef);
    double t1 = app_clock_seconds();
    memcpy(out, in, sizeof(float) * (size_t)n * n);
    __asm__ volatile("" ::"r"(out) : "memory");
    double t2 = app_clock_seconds();
    if (r >= 0) tf[r] = t1 - t0, tc[r] = t2 - t1;
  }
  transform_plan_destroy(plan);
  *fused_ms = 1e3 * app_median(tf, PAIRS);
  *copy_ms = 1e3 * app_median(tc, PAIRS);
}

static double time_gsl(int n, const float *in) {
  gsl_wavelet *w = gsl_wavelet_alloc(gsl_wavelet_bspline, 202);
  gsl_wavelet_workspace *work = gsl_wavelet_workspace_alloc((size_t)n);
  double *data = malloc(sizeof(double) * (size_t)n * n);
  if (!w || !work || !data) { /* NAN: the row says the reference was not timed */
    free(data);
    if (work) gsl_wavelet_workspace_free(work);
    if (w) gsl_wavelet_free(w);
    return NAN;
  }
  int reps = n >= 1024 ? 7 : 11;
  double t[MAX_REPS];
  for (int r = -1; r < reps; r++) {
    for (size_t i = 0; i < (size_t)n * n; i++) data[i] = in[i];
    double t0 = app_clock_seconds();
    gsl_wavelet2d_nstransform_forward(w, data, (size_t)n, (size_t)n, (size_t)n, work);
    double dt = app_clock_seconds() - t0;
    if (r >= 0) t[r] = dt;
  }
  free(data);
  gsl_wavelet_workspace_free(work);
  gsl_wavelet_free(w);
  return 1e3 * app_median(t, reps);
}

/* PyWavelets wavedec2(bior2.2, level 3, float32), timed inside python on the same data
 * (written to temporary files); NAN where /usr/bin/python3 or pywt is missing. */
static void time_pywt(float *const *data, double *ms) {
  char paths[3][64];
  for (int s = 0; s < 3; s++) {
    ms[s] = NAN;
    snprintf(paths[s], sizeof paths[s], "/tmp/fogpipe_bench_pywt_%ld_%d.f32", (long)getpid(), s);
    FILE *f = fopen(paths[s], "wb");
    size_t count = (size_t)sizes[s] * sizes[s];
    if (!f) return;
    size_t written = fwrite(data[s], sizeof(float), count, f);
    fclose(f);
    if (written != count) return;
  }
  if (access("/usr/bin/python3", X_OK) == 0) {
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "/usr/bin/python3 -c '\n"
             "import sys, time\nimport numpy as np, pywt\n"
             "for path, n, reps in zip(sys.argv[1::3], sys.argv[2::3], sys.argv[3::3]):\n"
             "    n = int(n); x = np.fromfile(path, dtype=np.float32).reshape(n, n)\n"
             "    for _ in range(2): pywt.wavedec2(x, \"bior2.2\", level=3)\n"
             "    ts = []\n"
             "    for _ in range(int(reps)):\n"
             "        t = time.perf_counter(); pywt.wavedec2(x, \"bior2.2\", level=3)\n"
             "        ts.append(time.perf_counter() - t)\n"
             "    print(sorted(ts)[len(ts) // 2] * 1e3)\n"
             "' %s 256 31 %s 512 15 %s 1024 9 2>/dev/null",
             paths[0], paths[1], paths[2]);
    FILE *p = popen(cmd, "r");
    if (p) {
      for (int s = 0; s < 3; s++)
        if (fscanf(p, "%lf", &ms[s]) != 1) ms[s] = NAN;
      pclose(p);
    }
  }
  for (int s = 0; s < 3; s++) unlink(paths[s]);
}

static double gbps(int n, double ms) { return 2.0 * 4.0 * n * (double)n / (ms * 1e-3) / 1e9; }

int bench_transform(int argc, char **argv) {
  const bench_command command = {
      .stage = "transform", .usage = "",
      .about = "Forward/inverse (3 levels, full decomposition) and one fused level at 256^2,\n"
               "512^2, 1024^2 for each basis, 1 and 2 threads, against GSL 2.7 (bspline 202,\n"
               "full), PyWavelets (wavedec2 bior2.2 level 3, float32) and memcpy.\n"
               "Last line: transform: speedup_vs_gsl=X speedup_vs_pywt=Y bandwidth_fraction=Z"};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  bench_print_build();
  float *data[3];
  for (int s = 0; s < 3; s++) /* aligned, as the pipeline's */
    data[s] = transform_alloc_floats((size_t)sizes[s] * sizes[s]);
  size_t big = (size_t)1024 * 1024;
  float *coef = transform_alloc_floats(big), *out = transform_alloc_floats(big);
  if (!data[0] || !data[1] || !data[2] || !coef || !out) {
    fprintf(stderr, "fogpipe bench transform: out of memory for the test fogmaps\n");
    for (int s = 0; s < 3; s++) free(data[s]);
    free(coef), free(out);
    return 1;
  }
  for (int s = 0; s < 3; s++) fill(data[s], sizes[s]);
  double pywt_ms[3];
  time_pywt(data, pywt_ms);
  printf("ms (GB/s = one read + one write of the fogmap); medians of 21..61 runs; symmetric,\n"
         "non-standard; single-pass levels (forward: all bases; inverse: haar, linear), their\n"
         "rows split between the threads with 2 threads (quadratic inverse: rows, then column\n"
         "strips, split likewise).\n");
  printf("%-6s %-9s %-3s %15s %15s %15s %15s %15s\n", "size", "basis", "thr", "fwd 3 levels",
         "inv 3 levels", "fwd full", "inv full", "fused level");
  double ours_full = NAN, ours_3 = NAN, fused = NAN, copy_1024 = NAN, gsl_1024 = NAN;
  warm_up_two_threads(data[1], coef, 0.2);
  for (int s = 0; s < 3; s++) {
    int n = sizes[s], full = transform_max_levels(n, n, TRANSFORM_SYMMETRIC);
    for (int b = 0; b < 3; b++)
      for (int threads = 1; threads <= 2; threads++) {
        double f3 = time_transform(n, 3, bases[b], threads, FORWARD, data[s], coef, out);
        double i3 = time_transform(n, 3, bases[b], threads, INVERSE, data[s], coef, out);
        double ff = time_transform(n, full, bases[b], threads, FORWARD, data[s], coef, out);
        double fi = time_transform(n, full, bases[b], threads, INVERSE, data[s], coef, out);
        double f1 = time_transform(n, 1, bases[b], threads, FORWARD, data[s], coef, out);
        printf("%4d^2 %-9s %-3d %7.3f (%5.1f) %7.3f (%5.1f) %7.3f (%5.1f) %7.3f (%5.1f) "
               "%7.3f (%5.1f)\n", n, basis_names[b], threads, f3, gbps(n, f3), i3, gbps(n, i3),
               ff, gbps(n, ff), fi, gbps(n, fi), f1, gbps(n, f1));
        if (n == 1024 && bases[b] == TRANSFORM_LINEAR && threads == 1)
          ours_full = ff, ours_3 = f3;
      }
    double copy = time_memcpy(n, data[s], out);
    double gsl = time_gsl(n, data[s]);
    printf("%4d^2 references: memcpy %.3f ms (%.1f GB/s); GSL bspline 202 full %.3f ms; "
           "pywt bior2.2 level 3 %.3f ms\n", n, copy, gbps(n, copy), gsl, pywt_ms[s]);
    if (n == 1024) {
      gsl_1024 = gsl;
      time_fused_vs_memcpy(n, data[s], coef, out, &fused, &copy_1024);
      printf("%4d^2 bandwidth: fused level (linear, 1 thread) %.3f ms vs memcpy %.3f ms, "
             "interleaved, medians of 101 pairs (64-byte aligned buffers, as the pipeline's)\n",
             n, fused, copy_1024);
      /* the same bytes 16 bytes past a line, where glibc's malloc puts large blocks */
      size_t slot = big + 16;
      float *shifted = transform_alloc_floats(3 * slot);
      if (shifted) {
        double fused_off, copy_off;
        memcpy(shifted + 4, data[s], sizeof(float) * big);
        time_fused_vs_memcpy(n, shifted + 4, shifted + slot + 4, shifted + 2 * slot + 4,
                             &fused_off, &copy_off);
        printf("%4d^2 bandwidth: fused level %.3f ms vs memcpy %.3f ms (%.2f) with every "
               "buffer 16 bytes past a 64-byte line (malloc's)\n", n, fused_off, copy_off,
               copy_off / fused_off);
        free(shifted);
      }
    }
  }
  for (int s = 0; s < 3; s++) free(data[s]);
  free(coef), free(out);
  printf("transform: speedup_vs_gsl=%.1f speedup_vs_pywt=%.1f bandwidth_fraction=%.2f\n",
         gsl_1024 / ours_full, pywt_ms[2] / ours_3, copy_1024 / fused);
  return 0;
}
