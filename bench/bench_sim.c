/* fogpipe bench sim: the FFT stable-fluid step against its FFT bound.
 *
 * At 256², 512² and 1024² (one thread; one size and scheme after another, the three parts
 * of each interleaved round by round so machine noise hits them alike), it times one full
 * fluid_sim_step, the step's own FFTW plans executed alone (forward r2c of u and v,
 * inverse c2r of them: what one step runs) and the step's own fused 3-field advection (u,
 * v, density, same scheme) alone. The medians give
 * ratio = step / (FFT + advection): how much the rest of the step (Fourier-space
 * forcing, viscosity and projection, wind phases, sources, clamp) costs on top of the
 * two unavoidable parts. Last line: `sim: step_ms_512=A ratio_to_fft_bound=B` for the
 * default scheme (the clamped cubic). The same ratio from the minimum times is printed
 * beside it: on a loaded machine the medians wander, the minima much less. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli_options.h"
#include "bench/bench.h"
#include "sim/sim.h"


typedef struct sim_figures {
  double step_ms, fft_ms, advect_ms;          /* medians */
  double step_min, fft_min, advect_min;       /* minima, ms */
} sim_figures;

static double min_of(const double *v, int n) {
  double m = v[0];
  for (int i = 1; i < n; i++) m = v[i] < m ? v[i] : m;
  return m;
}

static int measure(int n, fluid_advection scheme, int rounds, sim_figures *out) {
  fog_error err;
  const fluid_emitter emitters[3] = {{0.25f * n, 0.5f * n, n / 40.0f, 2.0f},
                                     {0.6f * n, 0.3f * n, n / 30.0f, 1.5f},
                                     {0.7f * n, 0.8f * n, n / 50.0f, 3.0f}};
  /* A realistic load: turbulence of n/16 cells/s and drift n/32 cells/s at dt 1/30
   * (about 0.5-2 cells per step), three emitters, relaxation and dissipation on. */
  fluid_sim_desc desc = fluid_sim_desc_default(n, n);
  desc.turbulence = n / 16.0f, desc.wind_drift_x = n / 32.0f, desc.viscosity = 0.05f;
  desc.seed = 11, desc.advection = scheme, desc.emitters = emitters, desc.emitter_count = 3;
  desc.relaxation = 0.05f, desc.dissipation = 0.02f;
  fluid_sim *sim = fluid_sim_create(&desc, &err);
  /* The FFT hook leaves an unnormalised velocity behind, so it runs on its own copy. */
  fluid_sim *probe = sim ? fluid_sim_create(&desc, &err) : NULL;
  if (!sim || !probe) {
    fprintf(stderr, "fogpipe bench sim: %s\n", err.message);
    fluid_sim_destroy(sim);
    return 1;
  }
  const int per_round = 5, total = rounds * per_round;
  double *step = malloc(sizeof(double) * total), *fft = malloc(sizeof(double) * total);
  double *adv = malloc(sizeof(double) * total);
  if (!step || !fft || !adv) {
    fprintf(stderr, "fogpipe bench sim: out of memory for %d timings\n", total);
    free(step), free(fft), free(adv);
    fluid_sim_destroy(sim);
    fluid_sim_destroy(probe);
    return 1;
  }
  /* Warm-up: caches, page faults, and a developed flow (1 s of simulated time). */
  for (int s = 0; s < 30; s++) fluid_sim_step(sim, &err), fluid_sim_step(probe, &err);
  for (int s = 0; s < 3; s++) fluid_sim_profile_transforms(probe);
  int k = 0;
  for (int r = 0; r < rounds; r++) {
    for (int i = 0; i < per_round; i++) {
      double t0 = app_clock_seconds();
      fluid_sim_step(sim, &err);
      step[k + i] = app_clock_seconds() - t0;
    }
    /* Each part alone, in the order the step runs them (advection, then the FFTs), so
     * each finds the caches as it does inside a step rather than warmed by a repeat of
     * itself. The advection hook reads the live sim's state and writes only buffers the
     * next step overwrites, so it measures the developed flow. */
    for (int i = 0; i < per_round; i++) {
      double t0 = app_clock_seconds();
      fluid_sim_profile_advection(sim);
      double t1 = app_clock_seconds();
      fluid_sim_profile_transforms(probe);
      double t2 = app_clock_seconds();
      adv[k + i] = t1 - t0;
      fft[k + i] = t2 - t1;
    }
    k += per_round;
  }
  out->step_min = 1e3 * min_of(step, total);
  out->fft_min = 1e3 * min_of(fft, total);
  out->advect_min = 1e3 * min_of(adv, total);
  out->step_ms = 1e3 * app_median(step, total);
  out->fft_ms = 1e3 * app_median(fft, total);
  out->advect_ms = 1e3 * app_median(adv, total);
  free(step), free(fft), free(adv);
  fluid_sim_destroy(sim);
  fluid_sim_destroy(probe);
  return 0;
}

int bench_sim(int argc, char **argv) {
  int rounds = 12;
  bool quick = false, rounds_given = false;
  const cli_option options[] = {
      {.kind = CLI_INT, .name = "--rounds", .value = "N", .target = &rounds, .min = 1,
       .max = 100000, .given = &rounds_given,
       .help = "timing rounds per size (each: 5 steps, 5 FFT pairs, 5 advections;\n"
               "default 12; 4 with --quick)"},
      {.kind = CLI_FLAG, .name = "--quick", .target = &quick,
       .help = "only 256^2 and 512^2, 4 rounds unless --rounds says (a smoke run)"},
  };
  const bench_command command = {.stage = "sim", .usage = "[--rounds N] [--quick]",
                                 .about = "The FFT stable-fluid step against its FFT bound.",
                                 .options = options,
                                 .option_count = sizeof options / sizeof options[0]};
  int exit_status = bench_parse(&command, argc, argv);
  if (exit_status >= 0) return exit_status;
  if (quick && !rounds_given) rounds = 4; /* --rounds was capped at 4 without a word */
  bench_print_build();
  char at_1024[32] = "";
  if (!quick) snprintf(at_1024, sizeof at_1024, " (%d at 1024^2)", (rounds + 1) / 2 * 5);
  printf("one thread; medians over %d timed calls per figure after warm-up%s;\n"
         "FFT = the step's r2c(u,v) + c2r(u,v) plans alone; advect = its fused u, v, density\n"
         "pass\n",
         rounds * 5, at_1024);
  printf("%-6s %-20s %9s %9s %10s %10s %7s %10s\n", "grid", "scheme", "step ms", "FFT ms",
         "advect ms", "bound ms", "ratio", "ratio(min)");
  const int sizes[3] = {256, 512, 1024};
  const fluid_advection schemes[4] = {FLUID_ADVECT_MONOTONE_CUBIC, FLUID_ADVECT_BILINEAR,
                                      FLUID_ADVECT_MACCORMACK,
                                      FLUID_ADVECT_MACCORMACK_BILINEAR};
  const char *names[4] = {"cubic (default)", "bilinear", "maccormack", "maccormack-bilinear"};
  double step_512 = 0, ratio_512 = 0;
  for (int si = 0; si < (quick ? 2 : 3); si++) {
    const int n = sizes[si];
    for (int s = 0; s < 4; s++) {
      /* 1024² is slow on this machine: the default scheme only, fewer rounds. */
      if (n == 1024 && s > 0) continue;
      sim_figures f;
      if (measure(n, schemes[s], n == 1024 ? (rounds + 1) / 2 : rounds, &f)) return 1;
      const double bound = f.fft_ms + f.advect_ms, ratio = f.step_ms / bound;
      printf("%-6d %-20s %9.3f %9.3f %10.3f %10.3f %7.3f %10.3f\n", n, names[s], f.step_ms,
             f.fft_ms, f.advect_ms, bound, ratio, f.step_min / (f.fft_min + f.advect_min));
      fflush(stdout);
      if (n == 512 && s == 0) step_512 = f.step_ms, ratio_512 = ratio;
    }
  }
  printf("sim: step_ms_512=%.3f ratio_to_fft_bound=%.3f\n", step_512, ratio_512);
  return 0;
}
