/* A heightmap is one channel of heights (app/render_frame.h): a grey PNG and the same grey
 * saved as grey with alpha, as RGB and as RGBA with equal colour channels give the same
 * heights, byte for byte (the alpha, whatever it holds, is not a height);
 * an RGB PNG whose channels differ is refused naming the config line, the file and a pixel
 * where they differ. An EXR of Y and A is its Y (it was refused, asking to name a channel
 * no key names), and a bad value is named as a height, not a density, also in an EXR of
 * Y and A; a heightmap past the terrain's largest grid is refused naming its line. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/config.h"
#include "app/render_frame.h"
#include "sim/image_io.h"
#include "sim/sim.h"
#include "test_util.h"

enum { W = 9, H = 7 };

static char dir[] = "/tmp/fogpipe-heightmap-XXXXXX";

/* Writes PNG `name` of `channels` (1: the grey heights; 3, 4: copies of them in every
 * channel, with pixel (5, 2)'s G raised by g_off) and a config naming it, and loads the
 * heightmap: the load's status, its heights into *out and its message into err. */
static int load(const char *name, int channels, const float *grey, float g_off, float **out,
                int *w, int *h, fog_error *err) {
  float pixels[W * H * 4];
  for (int i = 0; i < W * H; i++)
    for (int c = 0; c < channels; c++)
      pixels[i * channels + c] = grey[i];
  if (channels >= 3) pixels[(2 * W + 5) * channels + 1] += g_off;
  char png[256], ini[256], text[512];
  snprintf(png, sizeof png, "%s/%s.png", dir, name);
  snprintf(ini, sizeof ini, "%s/%s.ini", dir, name);
  fog_error werr;
  if (channels == 2) { /* grey + alpha: 8-bit samples (image_write_png takes 1, 3 or 4) */
    unsigned char samples[W * H * 2];
    for (int i = 0; i < W * H; i++) {
      samples[2 * i] = (unsigned char)(grey[i] * 255.0f + 0.5f);
      samples[2 * i + 1] = (unsigned char)(255 - (i * 53) % 256); /* not the grey */
    }
    CHECK(png_write_samples(png, W, H, 2, 8, false, samples, &werr) == 0, "%s", werr.message);
  } else {
    CHECK(image_write_png(png, W, H, channels, pixels, &werr) == 0, "%s", werr.message);
  }
  snprintf(text, sizeof text, "; %s\n[terrain]\nheightmap = %s\n", name, png);
  FILE *f = fopen(ini, "w");
  CHECK(f != NULL, "cannot write %s", ini);
  if (!f) return 1;
  fputs(text, f);
  fclose(f);
  scene_config cfg;
  CHECK(scene_config_load(ini, &cfg, err) == 0, "%s: %s", ini, err->message);
  return render_frame_load_heightmap(&cfg, out, w, h, err);
}

int main(void) {
  if (!test_scratch_folder(dir)) return 1;
  float grey[W * H];
  for (int i = 0; i < W * H; i++) grey[i] = (float)((i * 37) % 256) / 255.0f;
  float *want = NULL, *got = NULL;
  int w, h;
  fog_error err = {0};
  CHECK(load("grey", 1, grey, 0.0f, &want, &w, &h, &err) == 0 && w == W && h == H,
        "grey PNG: %s", err.message);
  if (want) {
    CHECK(load("grey_alpha", 2, grey, 0.0f, &got, &w, &h, &err) == 0 && w == W && h == H &&
              !memcmp(got, want, sizeof(float) * W * H),
          "grey + alpha: %s", got ? "other heights" : err.message);
    free(got);
  }
  const int colour[2] = {3, 4};
  for (int k = 0; k < 2 && want; k++) {
    char name[16];
    snprintf(name, sizeof name, "colour%d", colour[k]);
    got = NULL;
    CHECK(load(name, colour[k], grey, 0.0f, &got, &w, &h, &err) == 0 && w == W && h == H &&
              !memcmp(got, want, sizeof(float) * W * H),
          "%d channels with R = G = B: %s", colour[k], got ? "other heights" : err.message);
    free(got);
    got = NULL;
    snprintf(name, sizeof name, "tinted%d", colour[k]);
    int status = load(name, colour[k], grey, 0.2f, &got, &w, &h, &err);
    CHECK(status != 0 && got == NULL && strstr(err.message, "[terrain] heightmap: ") &&
              strstr(err.message, name) && strstr(err.message, "differ at pixel (5, 2)"),
          "%d channels, G raised at (5, 2): %s", colour[k], status ? err.message : "accepted");
    free(got);
  }
  /* an EXR of Y (the heights) and A */
  if (want) {
    char exr[400], ini[400];
    snprintf(exr, sizeof exr, "%s/grey_alpha.exr", dir);
    snprintf(ini, sizeof ini, "%s/grey_alpha_exr.ini", dir);
    float alpha[W * H];
    for (int i = 0; i < W * H; i++) alpha[i] = 1.0f;
    const image_channel channels[2] = {{.name = "Y", .pixels = want}, {.name = "A", .pixels = alpha}};
    fog_error werr = {0};
    CHECK(image_write_exr(exr, W, H, channels, 2, &werr) == 0, "%s", werr.message);
    char text[600];
    snprintf(text, sizeof text, "[terrain]\nheightmap = %s\n", exr);
    test_write_text(ini, text);
    scene_config cfg;
    got = NULL;
    CHECK(scene_config_load(ini, &cfg, &err) == 0 &&
              render_frame_load_heightmap(&cfg, &got, &w, &h, &err) == 0 && w == W && h == H &&
              !memcmp(got, want, sizeof(float) * W * H),
          "an EXR of Y and A: %s", got ? "other heights" : err.message);
    free(got);
    /* a negative height: named as a height */
    float bad[W * H];
    memcpy(bad, want, sizeof bad);
    bad[W + 1] = -0.01f;
    const image_channel one = {.name = "Y", .pixels = bad};
    CHECK(image_write_exr(exr, W, H, &one, 1, &werr) == 0, "%s", werr.message);
    got = NULL;
    CHECK(scene_config_load(ini, &cfg, &err) == 0 &&
              render_frame_load_heightmap(&cfg, &got, &w, &h, &err) != 0 &&
              strstr(err.message, "pixel (1, 1) is negative") &&
              strstr(err.message, "heights must be"),
          "a negative height: %s", got ? "accepted" : err.message);
    free(got);
    /* the same in an EXR of Y and A: the bad height is said (it was "EXR has 2 channels;
     * name the one to load", a channel no key names) */
    const image_channel two[2] = {{.name = "Y", .pixels = bad}, {.name = "A", .pixels = alpha}};
    CHECK(image_write_exr(exr, W, H, two, 2, &werr) == 0, "%s", werr.message);
    got = NULL;
    CHECK(scene_config_load(ini, &cfg, &err) == 0 &&
              render_frame_load_heightmap(&cfg, &got, &w, &h, &err) != 0 &&
              strstr(err.message, "pixel (1, 1) is negative") &&
              !strstr(err.message, "name the one"),
          "a negative height in an EXR of Y and A: %s", got ? "accepted" : err.message);
    free(got);
    /* past the terrain's 7681 x 7681 vertices: refused naming the line, key and file (the
     * terrain refused it naming none of them) */
    enum { BIG = 7682 };
    unsigned char *samples = calloc((size_t)BIG * BIG, 1);
    char big[400];
    snprintf(big, sizeof big, "%s/big.png", dir);
    CHECK(samples && png_write_samples(big, BIG, BIG, 1, 8, false, samples, &werr) == 0,
          "%s", werr.message);
    free(samples);
    snprintf(text, sizeof text, "[terrain]\nheightmap = %s\n", big);
    test_write_text(ini, text);
    got = NULL;
    CHECK(scene_config_load(ini, &cfg, &err) == 0 &&
              render_frame_load_heightmap(&cfg, &got, &w, &h, &err) != 0 &&
              strstr(err.message, ":2: [terrain] heightmap: ") && strstr(err.message, "big.png") &&
              strstr(err.message, "at most 7681 x 7681"),
          "a 7682 x 7682 heightmap: %s", got ? "accepted" : err.message);
    free(got);
  }
  free(want);
  test_remove_tree(dir);
  return test_finish("test_heightmap_channels");
}
