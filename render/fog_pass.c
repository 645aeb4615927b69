/* The GL fog pass (see fog_pass.h). The CPU side computes, in double and camera-relative,
 * everything the shader needs in float (render/shaders/fog_integral.glsl). */
#include "render/fog_pass.h"

#include <math.h>
#include <stddef.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/fog_cell_poly.h"
#include "render/fog_occupancy.h"
#include "render/fog_rbf_tiles.h"
#include "render/gl_util.h"

/* A variant is one compiled program (fog_pass_variant below). A draw uses one or two, the
 * render bench a few dozen; they are kept, looked up by key. */
#define FOG_PASS_MAX_VARIANTS 256

typedef struct fog_pass_variant_entry {
  uint64_t key;
  GLuint program;
} fog_pass_variant_entry;

typedef struct fog_pass_slot {
  GLuint texture; /* R32F coefficients: the hardware-filtered variant */
  GLuint cells;   /* RGBA32F cell polynomials (render/fog_cell_poly.h): the manual variant */
  int width, height, degree;
  int cells_width, cells_height; /* texels */
  GLuint occupancy; /* R32F block bounds (render/fog_occupancy.h): empty-space skipping */
  int occupancy_width, occupancy_height; /* blocks */
  double empty_share; /* of the blocks: bound 0 */
  double origin_u, origin_v, spacing;
} fog_pass_slot;

struct fog_pass {
  fog_pass_variant_entry variants[FOG_PASS_MAX_VARIANTS];
  int variant_count;
  fog_pass_slot slots[FOG_PASS_MAX_GRIDS];
  /* LOD draws read the slots as layers of one 2D array texture (fog_integral.glsl,
   * FOG_SINGLE_GRID): layer k = slot k, zero beyond the slot's size. Rebuilt by copies on
   * the first LOD draw after an upload (layers_stale). */
  GLuint layers;
  int layers_width, layers_height, layers_count;
  GLuint cell_layers; /* the same for the cell polynomials */
  int cell_layers_width, cell_layers_height, cell_layers_count;
  GLuint occupancy_layers; /* and for the block bounds */
  int occupancy_layers_width, occupancy_layers_height, occupancy_layers_count;
  bool layers_stale;
  float *cell_scratch; /* fog_cell_poly_build's output before upload; grows, never shrinks */
  size_t cell_scratch_texels;
  /* FOG_MODEL_VOLUME: the density as a 3D texture and its placement (fog_pass_upload_grid3d). */
  GLuint grid3d;
  volume_grid_desc grid3d_place; /* its size and placement; values not kept */
  GLuint grid3d_occupancy;       /* R32F brick bounds (render/fog_occupancy.h) */
  int grid3d_bricks[3];
  double grid3d_empty_share;     /* of the bricks: bound 0 */
  /* This GL's texture size limits, asked once: uploads past them fail naming the size, not
   * with a bare GL_INVALID_VALUE. */
  GLint max_texture_size, max_3d_texture_size;
  GLint max_texture_buffer_size; /* texels: the Gaussians' tile lists are one buffer texture */
  long loop_cap; /* gl_util_loop_cap at creation (fog_pass_set_loop_cap) */
  /* The sun's optical-depth volume (fog_pass_upload_sun_shadow): R32F 3D texture and its
   * placement (optical_depth not kept). */
  GLuint sun_shadow;
  fog_sun_shadow sun_shadow_place;
  /* resolution_divisor > 1: the reduced pass's target (RGBA32F: optical depth, distance,
   * extinction at the surface). */
  gl_target reduced;
  /* FOG_MODEL_RBF: the Gaussians (RGBA32F buffer texture, two texels each) and the per-tile
   * lists (render/fog_rbf_tiles.h: R32UI buffer texture of indices, RG32UI 2D ranges). */
  GLuint rbf_buffer, rbf_texture, rbf_index_buffer, rbf_index_texture, rbf_ranges;
  int rbf_ranges_width, rbf_ranges_height;
  fog_rbf_tiles rbf_tiles;
  float *rbf_scratch;
  int rbf_scratch_count;
  /* FOG_INTEGRATOR_FROXEL: the integrated grid (RGBA32F 3D: in-scatter, transmittance to
   * each slice's far face) and the attachment-less framebuffer its fill is drawn with. */
  GLuint froxel_volume, froxel_framebuffer;
  int froxel_size[3];
  /* FOG_MODEL_PERLIN: the octaves' texels (fog_pass_upload_perlin) and their size. */
  GLuint perlin_texture;
  int perlin_size, perlin_octaves;
};

/* One compiled program: every draw setting the shader takes as a compile-time constant.
 * llvmpipe executes both sides of a branch under a mask (and the GLSL switches on these
 * settings inside the per-piece code), so each setting as a constant removes the other
 * cases' work from every piece; J as a constant makes the LOD levels straight-line code
 * (docs/integral.md, Performance). Describe one with designated initialisers; its key
 * (fog_pass_variant_key) and its #define block both come from variant_fields. */
typedef struct fog_pass_variant {
  int fetch_hardware;     /* FOG_FETCH_HARDWARE: 1 GL_LINEAR, 0 texelFetch */
  int integrator;         /* FOG_INTEGRATOR: fog_integrator */
  int degree;             /* FOG_DEGREE: the grids' B-spline degree */
  int profile_kind;       /* FOG_PROFILE_KIND: fog_profile_kind */
  int profile_degree;     /* FOG_PROFILE_DEGREE: the B-spline profile's, else 0 */
  int single_grid;        /* FOG_SINGLE_GRID: 1 no LOD (slot 0 alone) */
  int model;              /* FOG_MODEL_KIND: fog_model_kind */
  int lod_method;         /* FOG_LOD_METHOD: fog_lod_method */
  int reduced;            /* FOG_REDUCED: 1 full resolution, 2 or 4 the reduced pass */
  int upsample;           /* FOG_UPSAMPLE: 1 the upsampling pass */
  int levels;             /* FOG_LEVELS: J, 0..FOG_MAX_LEVELS */
  int sun_shadow;         /* FOG_SUN_SHADOW: fog_sun_shadow_kind */
  int surface_sun;        /* FOG_SURFACE_SUN: 1 the fog shadows the surfaces */
  int shafts;             /* FOG_SHAFTS: 1 the sun's shadow map in the fog */
  int skip;               /* FOG_SKIP: 1 empty-space skipping in the fogmap walk */
  int lamps;              /* FOG_LAMPS: 1 point and spot lights (fog_lamps.glsl) */
  int lamp_integral;      /* FOG_LAMP_INTEGRAL: fog_lamp_integral */
  int surface_lamps;      /* FOG_SURFACE_LAMPS: 1 the fog dims the lamps' light on surfaces */
  int froxel;             /* FOG_FROXEL: 0 none, 1 the froxel grid's fill, 2 its lookup */
  int shadow_nodes;       /* FOG_SHADOW_NODES: the light mean's nodes a segment or piece */
  int shadow_pieces;      /* FOG_SHADOW_PIECES: 1 the mean per piece of the exact walk */
  int shaft_samples;      /* FOG_SHAFT_SAMPLES: V's points a segment (1: at the nodes) */
  int lamp_shadows;       /* FOG_LAMP_SHADOWS: 1 the lamps' shadow cubes (lamp_shadow.glsl) */
  int lamp_spots;         /* FOG_LAMP_SPOTS: 1 a spot among the lamps (its pieces cut at its
                             cones: point lamps alone skip that code, 5 % of their time) */
  int quadrics_beside;    /* FOG_QUADRICS_BESIDE: 1 quadric volumes beside the model's fog */
  int quadric_noise;      /* FOG_QUADRIC_NOISE: 1 noise inside the quadric volumes (compiled
                             only then: llvmpipe runs an untaken branch's body under a mask,
                             and the turbulence doubled the homogeneous volumes' time) */
} fog_pass_variant;

static const struct {
  const char *define;
  size_t offset;
  int bits; /* of the key */
} variant_fields[] = {
    {"FOG_FETCH_HARDWARE", offsetof(fog_pass_variant, fetch_hardware), 1},
    {"FOG_INTEGRATOR", offsetof(fog_pass_variant, integrator), 1},
    {"FOG_DEGREE", offsetof(fog_pass_variant, degree), 2},
    {"FOG_PROFILE_KIND", offsetof(fog_pass_variant, profile_kind), 2},
    {"FOG_PROFILE_DEGREE", offsetof(fog_pass_variant, profile_degree), 2},
    {"FOG_SINGLE_GRID", offsetof(fog_pass_variant, single_grid), 1},
    {"FOG_MODEL_KIND", offsetof(fog_pass_variant, model), 4},
    {"FOG_LOD_METHOD", offsetof(fog_pass_variant, lod_method), 1},
    {"FOG_REDUCED", offsetof(fog_pass_variant, reduced), 3},
    {"FOG_UPSAMPLE", offsetof(fog_pass_variant, upsample), 1},
    {"FOG_LEVELS", offsetof(fog_pass_variant, levels), 3},
    {"FOG_SUN_SHADOW", offsetof(fog_pass_variant, sun_shadow), 2},
    {"FOG_SURFACE_SUN", offsetof(fog_pass_variant, surface_sun), 1},
    {"FOG_SHAFTS", offsetof(fog_pass_variant, shafts), 1},
    {"FOG_SKIP", offsetof(fog_pass_variant, skip), 1},
    {"FOG_LAMPS", offsetof(fog_pass_variant, lamps), 1},
    {"FOG_LAMP_INTEGRAL", offsetof(fog_pass_variant, lamp_integral), 2},
    {"FOG_SURFACE_LAMPS", offsetof(fog_pass_variant, surface_lamps), 1},
    {"FOG_FROXEL", offsetof(fog_pass_variant, froxel), 2},
    {"FOG_SHADOW_NODES", offsetof(fog_pass_variant, shadow_nodes), 3},
    {"FOG_SHADOW_PIECES", offsetof(fog_pass_variant, shadow_pieces), 1},
    {"FOG_SHAFT_SAMPLES", offsetof(fog_pass_variant, shaft_samples), 5},
    {"FOG_LAMP_SHADOWS", offsetof(fog_pass_variant, lamp_shadows), 1},
    {"FOG_LAMP_SPOTS", offsetof(fog_pass_variant, lamp_spots), 1},
    {"FOG_QUADRICS_BESIDE", offsetof(fog_pass_variant, quadrics_beside), 1},
    {"FOG_QUADRIC_NOISE", offsetof(fog_pass_variant, quadric_noise), 1},
};
#define VARIANT_FIELD_COUNT (int)(sizeof variant_fields / sizeof variant_fields[0])
_Static_assert(FOG_MODEL_COUNT <= 16 && FOG_MAX_LEVELS < 8 && FOG_PROFILE_BSPLINE < 4 &&
                   FOG_PASS_MAX_SHAFT_SAMPLES < 32 &&
                   FOG_SUN_SHADOW_OPAQUE < 4 && FOG_LAMP_MARCH < 4,
               "a fog_pass_variant field outgrew its bits of the key");

static int variant_field(const fog_pass_variant *v, int f) {
  return *(const int *)((const char *)v + variant_fields[f].offset);
}

/* The fields packed into bits, in variant_fields' order (43 of the 64; fog_pass_create
 * checks the sum). */
static int variant_key_bits(void) {
  int bits = 0;
  for (int f = 0; f < VARIANT_FIELD_COUNT; f++) bits += variant_fields[f].bits;
  return bits;
}

static uint64_t fog_pass_variant_key(const fog_pass_variant *v) {
  uint64_t key = 0;
  int shift = 0;
  for (int f = 0; f < VARIANT_FIELD_COUNT; f++) {
    key |= (uint64_t)(variant_field(v, f) & ((1 << variant_fields[f].bits) - 1)) << shift;
    shift += variant_fields[f].bits;
  }
  return key;
}

/* Builds one variant: the fragment text with its #defines inserted after the #version line. */
static GLuint fog_pass_program(const fog_pass_variant *v, uint64_t key, fog_error *err) {
  char *vs = gl_util_shader_text("fog_pass_vs.glsl", err);
  if (!vs) return 0;
  char *fs = gl_util_shader_text("fog_pass_fs.glsl", err);
  if (!fs) {
    free(vs);
    return 0;
  }
  char defines[1024];
  size_t used = 0;
  for (int f = 0; f < VARIANT_FIELD_COUNT && used < sizeof defines; f++)
    used += (size_t)snprintf(defines + used, sizeof defines - used, "#define %s %d\n",
                             variant_fields[f].define, variant_field(v, f));
  if (used >= sizeof defines) { /* a truncated block would leave a setting at 0 unseen */
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: the variant's #defines outgrew their %zu bytes", sizeof defines);
    free(vs);
    free(fs);
    return 0;
  }
  const char *eol = strchr(fs, '\n');
  size_t head = eol ? (size_t)(eol - fs) + 1 : 0;
  size_t total = strlen(fs) + strlen(defines) + 1;
  char *text = malloc(total);
  GLuint program = 0;
  if (text) {
    memcpy(text, fs, head);
    strcpy(text + head, defines);
    strcat(text, fs + head);
    char label[64];
    snprintf(label, sizeof label, "fog_pass_fs.glsl (variant %#llx)", (unsigned long long)key);
    program = gl_util_program_from_source(label, vs, text, err);
  } else {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fog pass: out of memory for shader text");
  }
  free(text);
  free(vs);
  free(fs);
  return program;
}

/* The program of a variant, compiled on its first use and kept (looked up by key). */
static GLuint fog_pass_variant_program(fog_pass *pass, const fog_pass_variant *v, fog_error *err) {
  const uint64_t key = fog_pass_variant_key(v);
  for (int i = 0; i < pass->variant_count; i++)
    if (pass->variants[i].key == key) return pass->variants[i].program;
  if (pass->variant_count == FOG_PASS_MAX_VARIANTS) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: more than %d shader variants (draw settings) in one pass",
             FOG_PASS_MAX_VARIANTS);
    return 0;
  }
  GLuint program = fog_pass_program(v, key, err);
  if (program)
    pass->variants[pass->variant_count++] = (fog_pass_variant_entry){key, program};
  return program;
}

static int pass_make(fog_pass **out, fog_error *err) {
  *out = NULL;
  fog_pass *pass = calloc(1, sizeof *pass);
  if (!pass) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fog pass: out of memory");
    return 1;
  }
  if (variant_key_bits() > 64) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: the variant fields take %d bits, more than the key's 64",
             variant_key_bits());
    free(pass);
    return 1;
  }
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &pass->max_texture_size);
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &pass->max_3d_texture_size);
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &pass->max_texture_buffer_size);
  if (gl_util_loop_cap(&pass->loop_cap, err)) {
    free(pass);
    return 1;
  }
  /* The default variant: manual fetch, exact, linear grid, slab profile, one grid. */
  const fog_pass_variant default_variant = {.degree = 1, .single_grid = 1,
                                            .model = FOG_MODEL_FOGMAP, .reduced = 1};
  if (!fog_pass_variant_program(pass, &default_variant, err)) {
    free(pass);
    return 1;
  }
  *out = pass;
  return 0;
}

fog_pass *fog_pass_create(fog_error *err) {
  fog_pass *pass;
  return pass_make(&pass, err) ? NULL : pass;
}

long fog_pass_loop_cap(const fog_pass *pass) { return pass->loop_cap; }
void fog_pass_set_loop_cap(fog_pass *pass, long cap) { pass->loop_cap = cap; }
double fog_pass_loops_allowed(const fog_pass *pass) {
  return (double)pass->loop_cap - FOG_PASS_LOOP_RESERVE;
}

void fog_pass_destroy(fog_pass *pass) {
  if (!pass) return;
  for (int i = 0; i < pass->variant_count; i++) glDeleteProgram(pass->variants[i].program);
  for (int i = 0; i < FOG_PASS_MAX_GRIDS; i++)
    if (pass->slots[i].texture) glDeleteTextures(1, &pass->slots[i].texture);
  for (int i = 0; i < FOG_PASS_MAX_GRIDS; i++)
    if (pass->slots[i].cells) glDeleteTextures(1, &pass->slots[i].cells);
  for (int i = 0; i < FOG_PASS_MAX_GRIDS; i++)
    if (pass->slots[i].occupancy) glDeleteTextures(1, &pass->slots[i].occupancy);
  if (pass->occupancy_layers) glDeleteTextures(1, &pass->occupancy_layers);
  if (pass->layers) glDeleteTextures(1, &pass->layers);
  if (pass->grid3d) glDeleteTextures(1, &pass->grid3d);
  if (pass->grid3d_occupancy) glDeleteTextures(1, &pass->grid3d_occupancy);
  if (pass->sun_shadow) glDeleteTextures(1, &pass->sun_shadow);
  if (pass->cell_layers) glDeleteTextures(1, &pass->cell_layers);
  if (pass->froxel_volume) glDeleteTextures(1, &pass->froxel_volume);
  if (pass->perlin_texture) glDeleteTextures(1, &pass->perlin_texture);
  if (pass->froxel_framebuffer) glDeleteFramebuffers(1, &pass->froxel_framebuffer);
  GLuint rbf_textures[3] = {pass->rbf_texture, pass->rbf_index_texture, pass->rbf_ranges};
  GLuint rbf_buffers[2] = {pass->rbf_buffer, pass->rbf_index_buffer};
  glDeleteTextures(3, rbf_textures); /* zeros are ignored */
  glDeleteBuffers(2, rbf_buffers);
  fog_rbf_tiles_destroy(&pass->rbf_tiles);
  free(pass->rbf_scratch);
  free(pass->cell_scratch);
  if (pass->reduced.framebuffer) gl_target_destroy(&pass->reduced);
  free(pass);
}

/* A texelFetch-only float texture of w x h texels filled from data: updated in place when
 * its size is unchanged, (re)allocated otherwise. Leaves it bound to GL_TEXTURE_2D. */
static void texel_texture_fill(GLuint *texture, int *width, int *height, GLenum internal_format,
                               GLenum format, int w, int h, const float *data) {
  if (*texture && *width == w && *height == h) {
    glBindTexture(GL_TEXTURE_2D, *texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, format, GL_FLOAT, data);
    return;
  }
  if (!*texture) glGenTextures(1, texture);
  glBindTexture(GL_TEXTURE_2D, *texture);
  glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal_format, w, h, 0, format, GL_FLOAT, data);
  gl_util_texture_sampling(GL_TEXTURE_2D, false);
  *width = w;
  *height = h;
}

int fog_pass_upload_grid(fog_pass *pass, int slot, const transform_grid *grid, fog_error *err) {
  if (slot < 0 || slot >= FOG_PASS_MAX_GRIDS) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: grid slot %d outside 0..%d", slot,
             FOG_PASS_MAX_GRIDS - 1);
    return 1;
  }
  if (grid->width <= 0 || grid->height <= 0 || !grid->coefficients || grid->degree < 0 ||
      grid->degree > 2 || !(grid->spacing > 0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: grid for slot %d is %dx%d, degree %d, spacing %g: expected a non-empty "
             "grid of degree 0..2 with positive spacing",
             slot, grid->width, grid->height, grid->degree, grid->spacing);
    return 1;
  }
  int cw, ch; /* the cell polynomials' texture (below) */
  fog_cell_poly_size(grid->width, grid->height, grid->degree, &cw, &ch);
  int largest = grid->width > grid->height ? grid->width : grid->height;
  if (cw > largest) largest = cw;
  if (ch > largest) largest = ch;
  if (largest > pass->max_texture_size) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "fog pass: a %dx%d grid needs a %d-texel texture side; this GL's largest is %d",
             grid->width, grid->height, largest, pass->max_texture_size);
    return 1;
  }
  fog_pass_slot *s = &pass->slots[slot];
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glActiveTexture(GL_TEXTURE0);
  if (s->texture && s->width == grid->width && s->height == grid->height) {
    glBindTexture(GL_TEXTURE_2D, s->texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, grid->width, grid->height, GL_RED, GL_FLOAT,
                    grid->coefficients);
  } else {
    if (!s->texture) glGenTextures(1, &s->texture);
    glBindTexture(GL_TEXTURE_2D, s->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, grid->width, grid->height, 0, GL_RED, GL_FLOAT,
                 grid->coefficients);
    /* GL_LINEAR for the hardware-filtered variant; the border (0) stands for the zero
     * coefficients outside the grid. texelFetch ignores both. */
    gl_util_texture_sampling(GL_TEXTURE_2D, true);
    s->width = grid->width;
    s->height = grid->height;
  }
  /* The cell polynomials of the manual variant (texelFetch only: no filtering, no border). */
  size_t texels = (size_t)cw * (size_t)ch;
  if (texels > pass->cell_scratch_texels) {
    float *grown = realloc(pass->cell_scratch, texels * 4 * sizeof(float));
    if (!grown) {
      glBindTexture(GL_TEXTURE_2D, 0);
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY,
               "fog pass: out of memory for the cell polynomials of a %dx%d grid", grid->width,
               grid->height);
      return 1;
    }
    pass->cell_scratch = grown;
    pass->cell_scratch_texels = texels;
  }
  fog_cell_poly_build(grid, pass->cell_scratch);
  texel_texture_fill(&s->cells, &s->cells_width, &s->cells_height, GL_RGBA32F, GL_RGBA, cw, ch,
                     pass->cell_scratch);
  /* The block bounds (fewer texels than the cell polynomials: the same scratch). */
  int ow, oh;
  fog_occupancy_size(grid->width, grid->height, grid->degree, &ow, &oh);
  s->empty_share = (double)fog_occupancy_build(grid, pass->cell_scratch) / ((double)ow * oh);
  texel_texture_fill(&s->occupancy, &s->occupancy_width, &s->occupancy_height, GL_R32F, GL_RED,
                     ow, oh, pass->cell_scratch);
  glBindTexture(GL_TEXTURE_2D, 0);
  pass->layers_stale = true;
  s->degree = grid->degree;
  s->origin_u = grid->origin_u;
  s->origin_v = grid->origin_v;
  s->spacing = grid->spacing;
  return gl_util_check("fog pass: grid upload", err);
}

int fog_pass_upload_grid3d(fog_pass *pass, const volume_grid_desc *grid, fog_error *err) {
  const int *d = grid->dim;
  if (d[0] < 1 || d[1] < 1 || d[2] < 1 || !grid->values) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: volume grid %dx%dx%d: expected positive sizes and values", d[0], d[1],
             d[2]);
    return 1;
  }
  /* With a ring of zero voxels around it (voxel i at texel i + 1), and each texel holding
   * its voxel (R) and the voxel at +x (G): the exact walk reads a cell's 8 corners in 4
   * texelFetch, always inside the texture (7.8 -> 5.4 ms on the plume against 8 R32F
   * reads, for twice the memory), and the march's hardware trilinear filter of R sees the
   * same zeros beyond the outer voxels. */
  const int pw = d[0] + 2, ph = d[1] + 2, pd = d[2] + 2;
  int largest = pw > ph ? (pw > pd ? pw : pd) : (ph > pd ? ph : pd);
  if (largest > pass->max_3d_texture_size) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "fog pass: a %dx%dx%d volume needs a %d-texel 3D texture side; this GL's largest "
             "is %d",
             d[0], d[1], d[2], largest, pass->max_3d_texture_size);
    return 1;
  }
  size_t padded_count = (size_t)pw * ph * pd;
  float *padded = calloc(2 * padded_count, sizeof *padded); /* RG: voxel and its +x neighbour */
  if (!padded) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fog pass: out of memory for the volume");
    return 1;
  }
  for (int k = 0; k < d[2]; k++)
    for (int j = 0; j < d[1]; j++)
      for (int i = 0; i < d[0]; i++) {
        float v = grid->values[((size_t)k * d[1] + j) * d[0] + i];
        size_t t = ((size_t)(k + 1) * ph + j + 1) * pw + i + 1;
        padded[2 * t] = v;
        padded[2 * (t - 1) + 1] = v; /* the texel at i - 1's +x neighbour */
      }
  bool same = pass->grid3d && !memcmp(pass->grid3d_place.dim, d, sizeof pass->grid3d_place.dim);
  if (!pass->grid3d) glGenTextures(1, &pass->grid3d);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, pass->grid3d);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (same)
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, pw, ph, pd, GL_RG, GL_FLOAT, padded);
  else
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RG32F, pw, ph, pd, 0, GL_RG, GL_FLOAT, padded);
  free(padded);
  gl_util_texture_sampling(GL_TEXTURE_3D, true); /* hardware trilinear (the march) */
  /* The bricks' bounds for empty-space skipping (fog_models.glsl). */
  int bricks[3];
  fog_bricks_size(d, bricks);
  float *bound = malloc((size_t)bricks[0] * bricks[1] * bricks[2] * sizeof *bound);
  if (!bound) {
    glBindTexture(GL_TEXTURE_3D, 0);
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fog pass: out of memory for the bricks");
    return 1;
  }
  pass->grid3d_empty_share =
      (double)fog_bricks_build(grid, bound) / ((double)bricks[0] * bricks[1] * bricks[2]);
  if (!pass->grid3d_occupancy) glGenTextures(1, &pass->grid3d_occupancy);
  glBindTexture(GL_TEXTURE_3D, pass->grid3d_occupancy);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, bricks[0], bricks[1], bricks[2], 0, GL_RED, GL_FLOAT,
               bound);
  free(bound);
  gl_util_texture_sampling(GL_TEXTURE_3D, false);
  memcpy(pass->grid3d_bricks, bricks, sizeof bricks);
  glBindTexture(GL_TEXTURE_3D, 0);
  pass->grid3d_place = *grid;
  pass->grid3d_place.values = NULL;
  return gl_util_check("fog pass: volume upload", err);
}

int fog_pass_upload_perlin(fog_pass *pass, const fog_perlin *perlin, fog_error *err) {
  const int n = perlin->desc.size, octaves = perlin->desc.octaves;
  if (!perlin->texels || n * octaves > pass->max_3d_texture_size) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "fog pass: Perlin octaves of %d^3 x %d texels: expected created octaves within "
             "GL's 3D texture size %d",
             n, octaves, pass->max_3d_texture_size);
    return 1;
  }
  if (!pass->perlin_texture) glGenTextures(1, &pass->perlin_texture);
  glBindTexture(GL_TEXTURE_3D, pass->perlin_texture);
  if (pass->perlin_size == n && pass->perlin_octaves == octaves) {
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n * octaves, GL_RED, GL_FLOAT,
                    perlin->texels);
  } else {
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, n, n, n * octaves, 0, GL_RED, GL_FLOAT,
                 perlin->texels);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glBindTexture(GL_TEXTURE_3D, 0);
  pass->perlin_size = n, pass->perlin_octaves = octaves;
  return gl_util_check("fog pass: Perlin upload", err);
}

int fog_pass_upload_sun_shadow(fog_pass *pass, const fog_sun_shadow *shadow, fog_error *err) {
  const int *n = shadow->size;
  if (!shadow->optical_depth || n[0] < 2 || n[1] < 2 || n[2] < 2) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: sun shadow volume %dx%dx%d: expected >= 2 samples per axis and values",
             n[0], n[1], n[2]);
    return 1;
  }
  int largest = n[0] > n[1] ? (n[0] > n[2] ? n[0] : n[2]) : (n[1] > n[2] ? n[1] : n[2]);
  if (largest > pass->max_3d_texture_size) {
    fog_fail(err, FOG_ERR_GRAPHICS,
             "fog pass: a %dx%dx%d sun shadow volume exceeds this GL's 3D texture side %d", n[0],
             n[1], n[2], pass->max_3d_texture_size);
    return 1;
  }
  bool same = pass->sun_shadow && !memcmp(pass->sun_shadow_place.size, n, sizeof shadow->size);
  if (!pass->sun_shadow) glGenTextures(1, &pass->sun_shadow);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_3D, pass->sun_shadow);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (same)
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED, GL_FLOAT,
                    shadow->optical_depth);
  else
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, n[0], n[1], n[2], 0, GL_RED, GL_FLOAT,
                 shadow->optical_depth);
  /* Across the sunlight a zero border (no fog beside the box), along it the edge samples
   * (nothing before the sun-side face, the whole column past the far one): what
   * fog_sun_shadow_depth_at assumes. */
  gl_util_set_sampling(GL_TEXTURE_3D,
                       &(gl_sampling){.filter = GL_LINEAR,
                                      .wrap = {GL_CLAMP_TO_BORDER, GL_CLAMP_TO_BORDER,
                                               GL_CLAMP_TO_EDGE},
                                      .border = {0, 0, 0, 0}});
  glBindTexture(GL_TEXTURE_3D, 0);
  pass->sun_shadow_place = *shadow;
  pass->sun_shadow_place.optical_depth = NULL;
  return gl_util_check("fog pass: sun shadow upload", err);
}

int fog_pass_upload_lod(fog_pass *pass, const fog_lod *lod, fog_error *err) {
  int J = lod->levels;
  if (J < 0 || 2 * J + 1 > FOG_PASS_MAX_GRIDS) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: %d LOD levels: expected 0..%d", J,
             FOG_MAX_LEVELS);
    return 1;
  }
  for (int l = 0; l <= J; l++)
    if (fog_pass_upload_grid(pass, l, &lod->approx[l], err)) return 1;
  for (int l = 1; l <= J; l++)
    if (fog_pass_upload_grid(pass, J + l, &lod->detail[l - 1], err)) return 1;
  return 0;
}

int fog_pass_upload_pyramid(fog_pass *pass, const fog_pyramid *pyramid, fog_error *err) {
  if (pyramid->has_details) {
    fog_lod lod = fog_pyramid_lod(pyramid, 1.0);
    return fog_pass_upload_lod(pass, &lod, err);
  }
  /* approximations only: slots 0..J (switching reads no more) */
  if (pyramid->levels < 0 || 2 * pyramid->levels + 1 > FOG_PASS_MAX_GRIDS) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: %d LOD levels: expected 0..%d",
             pyramid->levels, FOG_MAX_LEVELS);
    return 1;
  }
  for (int l = 0; l <= pyramid->levels; l++)
    if (fog_pass_upload_grid(pass, l, &pyramid->approx[l], err)) return 1;
  return 0;
}

static GLint fog_loc(GLuint program, const char *name) { return glGetUniformLocation(program, name); }

/* The texture unit of each sampler of fog_pass_fs.glsl. */
enum fog_pass_unit {
  UNIT_SURFACE_COLOUR = 0,
  UNIT_SURFACE_DISTANCE,
  UNIT_GRIDS, /* fog_grids[k] on UNIT_GRIDS + k */
  UNIT_GRID_LAYERS = UNIT_GRIDS + FOG_PASS_MAX_GRIDS,
  UNIT_REDUCED,
  UNIT_REDUCED_LAMPS,
  UNIT_CELLS,
  UNIT_CELL_LAYERS,
  UNIT_OCCUPANCY,
  UNIT_OCCUPANCY_LAYERS,
  UNIT_GRID3D,
  UNIT_GRID3D_OCCUPANCY,
  UNIT_SUN_SHADOW,
  UNIT_SURFACE_SUN,
  UNIT_SURFACE_LAMPS,
  UNIT_SUN_VISIBILITY,
  UNIT_RBF_DATA,
  UNIT_RBF_INDICES,
  UNIT_RBF_TILES,
  UNIT_FROXEL,
  UNIT_PERLIN,
  UNIT_LAMP_SHADOWS,
  UNIT_COUNT
};
/* Unit indices stay below GL 4.3's guaranteed 96 combined units; a variant samples far
 * fewer at once than llvmpipe's 32 per stage (the fogmap's 2J + 1 grids and its walk's
 * tables, or another model's few textures, plus the light's). */
_Static_assert(UNIT_COUNT <= 48, "the fog pass needs more texture units than GL 4.3 offers");

static bool fog_pass_has_surface_lamps(const fog_pass_params *params);

/* Binds texture to unit and points sampler `name` of prog at it. */
static void bind_sampler(GLuint prog, const char *name, int unit, GLenum target,
                         GLuint texture) {
  glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
  glBindTexture(target, texture);
  glUniform1i(fog_loc(prog, name), unit);
}

/* A 2D array texture of w x h x count texels, (re)allocated only when that changes.
 * filtered: GL_LINEAR with a zero border (the hardware-filtered variant's coefficients);
 * otherwise GL_NEAREST (texelFetch only). */
static void array_texture_fit(GLuint *texture, int *width, int *height, int *count_now,
                              GLenum internal_format, GLenum format, int w, int h, int count,
                              bool filtered) {
  if (*texture && *width == w && *height == h && *count_now == count) return;
  if (!*texture) glGenTextures(1, texture);
  glBindTexture(GL_TEXTURE_2D_ARRAY, *texture);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, (GLint)internal_format, w, h, count, 0, format, GL_FLOAT,
               NULL);
  gl_util_texture_sampling(GL_TEXTURE_2D_ARRAY, filtered);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  *width = w;
  *height = h;
  *count_now = count;
}

/* Slots 0..count-1 into the layers of pass->layers (reallocated only when the largest slot
 * size or the count changes; zero-filled, so texelFetch and GL_LINEAR read 0 beyond a
 * smaller grid exactly as the border colour of its own texture would give). */
static int fog_pass_update_layers(fog_pass *pass, int count, fog_error *err) {
  if (!pass->layers_stale && pass->layers && pass->layers_count == count) return 0;
  int w = 1, h = 1, cw = 1, ch = 1, ow = 1, oh = 1;
  for (int k = 0; k < count; k++) {
    if (pass->slots[k].occupancy_width > ow) ow = pass->slots[k].occupancy_width;
    if (pass->slots[k].occupancy_height > oh) oh = pass->slots[k].occupancy_height;
    if (pass->slots[k].width > w) w = pass->slots[k].width;
    if (pass->slots[k].height > h) h = pass->slots[k].height;
    if (pass->slots[k].cells_width > cw) cw = pass->slots[k].cells_width;
    if (pass->slots[k].cells_height > ch) ch = pass->slots[k].cells_height;
  }
  glActiveTexture(GL_TEXTURE0);
  array_texture_fit(&pass->layers, &pass->layers_width, &pass->layers_height,
                    &pass->layers_count, GL_R32F, GL_RED, w, h, count, true);
  array_texture_fit(&pass->cell_layers, &pass->cell_layers_width, &pass->cell_layers_height,
                    &pass->cell_layers_count, GL_RGBA32F, GL_RGBA, cw, ch, count, false);
  array_texture_fit(&pass->occupancy_layers, &pass->occupancy_layers_width,
                    &pass->occupancy_layers_height, &pass->occupancy_layers_count, GL_R32F,
                    GL_RED, ow, oh, count, false);
  static const float zero[4] = {0, 0, 0, 0};
  glClearTexImage(pass->occupancy_layers, 0, GL_RED, GL_FLOAT, zero);
  glClearTexImage(pass->layers, 0, GL_RED, GL_FLOAT, zero);
  glClearTexImage(pass->cell_layers, 0, GL_RGBA, GL_FLOAT, zero);
  for (int k = 0; k < count; k++) {
    const fog_pass_slot *s = &pass->slots[k];
    if (s->texture)
      glCopyImageSubData(s->texture, GL_TEXTURE_2D, 0, 0, 0, 0, pass->layers, GL_TEXTURE_2D_ARRAY,
                         0, 0, 0, k, s->width, s->height, 1);
    if (s->cells)
      glCopyImageSubData(s->cells, GL_TEXTURE_2D, 0, 0, 0, 0, pass->cell_layers,
                         GL_TEXTURE_2D_ARRAY, 0, 0, 0, k, s->cells_width, s->cells_height, 1);
    if (s->occupancy)
      glCopyImageSubData(s->occupancy, GL_TEXTURE_2D, 0, 0, 0, 0, pass->occupancy_layers,
                         GL_TEXTURE_2D_ARRAY, 0, 0, 0, k, s->occupancy_width,
                         s->occupancy_height, 1);
  }
  pass->layers_stale = false;
  return gl_util_check("fog pass: LOD layers", err);
}

/* The fog's shadow on itself and on the surfaces (fog_light.glsl). */
static void fog_pass_sun_shadow_uniforms(const fog_pass *pass, GLuint prog, const camera *cam,
                                         const fog_pass_params *params) {
  /* Early termination (fog_pass_params.transmittance_cutoff): the walks and the shadow's
   * mean stop past this optical depth. */
  const double limit = fog_pass_depth_limit(params->walk.transmittance_cutoff);
  glUniform1f(fog_loc(prog, "fog_depth_limit"), limit < 1e30 ? (float)limit : 1e30f);
  glUniform1i(fog_loc(prog, "fog_shadow_steps"), params->shadow_steps);
  if (params->model == FOG_MODEL_PERLIN || params->model == FOG_MODEL_VOLUME ||
      params->model == FOG_MODEL_FOGMAP) {
    /* the per-piece mean's rule */
    double x[FOG_PIECE_MAX_NODES], w[FOG_PIECE_MAX_NODES],
        partial[FOG_PIECE_MAX_NODES][FOG_PIECE_MAX_NODES] = {{0}};
    int n = params->shadow_nodes >= 1 && params->shadow_nodes <= FOG_PIECE_MAX_NODES
                ? params->shadow_nodes : 1;
    fog_gauss_rule(n, x, w, partial);
    float xf[4] = {0}, wf[4] = {0}, pf[16] = {0};
    for (int j = 0; j < n; j++) {
      xf[j] = (float)x[j], wf[j] = (float)w[j];
      for (int q = 0; q < n; q++) pf[4 * j + q] = (float)partial[j][q]; /* m[j][q] */
    }
    glUniform1fv(fog_loc(prog, "fog_piece_x"), 4, xf);
    glUniform1fv(fog_loc(prog, "fog_piece_w"), 4, wf);
    glUniformMatrix4fv(fog_loc(prog, "fog_piece_partial"), 1, GL_FALSE, pf);
  }
  if (params->shafts) {
    const sun_shadow_map *map = params->shafts;
    double m[4][4];
    float rows[16];
    sun_shadow_map_matrix(map, cam->position, m);
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) rows[4 * r + c] = (float)m[r][c];
    bind_sampler(prog, "fog_sun_visibility", UNIT_SUN_VISIBILITY, GL_TEXTURE_2D, map->texture);
    glUniformMatrix4fv(fog_loc(prog, "fog_sun_visibility_from_relative"), 1, GL_TRUE, rows);
    glUniform1f(fog_loc(prog, "fog_sun_visibility_bias"),
                (float)(sun_shadow_map_texel(map) / (map->hi[2] - map->lo[2])));
  }
  if (params->surface_sun)
    bind_sampler(prog, "fog_surface_sun", UNIT_SURFACE_SUN, GL_TEXTURE_2D, params->surface_sun);
  if (fog_pass_has_surface_lamps(params))
    bind_sampler(prog, "fog_surface_lamps", UNIT_SURFACE_LAMPS, GL_TEXTURE_2D,
                 params->surface_lamps);
  if (params->self_shadow != FOG_SUN_SHADOW_VOLUME) return;
  const fog_sun_shadow *s = &pass->sun_shadow_place;
  double m[3][3], offset[3];
  fog_sun_shadow_tex_map(s, m, offset);
  float rows[9], at_camera[3];
  for (int a = 0; a < 3; a++) {
    double t = offset[a]; /* in double: the camera may be far from the volume */
    for (int c = 0; c < 3; c++) {
      rows[3 * a + c] = (float)m[a][c];
      t += m[a][c] * (cam->position[c] - s->origin[c]);
    }
    at_camera[a] = (float)t;
  }
  bind_sampler(prog, "fog_sun_shadow_map", UNIT_SUN_SHADOW, GL_TEXTURE_3D, pass->sun_shadow);
  glUniformMatrix3fv(fog_loc(prog, "fog_sun_shadow_to_tex"), 1, GL_TRUE, rows);
  glUniform3f(fog_loc(prog, "fog_sun_shadow_tex_camera"), at_camera[0], at_camera[1],
              at_camera[2]);
}

/* The lamps' in-scatter runs where there are lamps and the fog scatters. */
static bool fog_pass_has_lamps(const fog_pass_params *params) {
  return params->lamps.count > 0 && params->sun.albedo > 0;
}

/* The fog dims the lamps' light on the surfaces (whatever the albedo: absorbing fog too). */
static bool fog_pass_has_surface_lamps(const fog_pass_params *params) {
  return params->lamps.count > 0 && params->surface_lamps != 0;
}

/* The lamps' shadow cubes (the scene pass's) serve the lamps in the fog or on the surfaces:
 * the cubes follow the lamps' order, one per lamp. */
static bool fog_pass_has_lamp_shadows(const fog_pass_params *params) {
  return (fog_pass_has_lamps(params) || fog_pass_has_surface_lamps(params)) &&
         params->lamp_shadows && params->lamp_shadows->count >= params->lamps.count;
}

/* The lamps (fog_lamps.glsl): camera-relative positions subtracted in double, a I. */
static void fog_pass_lamp_uniforms(GLuint prog, const camera *cam, const fog_pass_params *params) {
  const fog_lamps *lamps = &params->lamps;
  fog_lamp_uniforms u;
  fog_lamps_pack(lamps, cam->position, params->sun.albedo, &u);
  glUniform1i(fog_loc(prog, "fog_lamp_count"), lamps->count);
  glUniform3fv(fog_loc(prog, "fog_lamp_position"), lamps->count, &u.position[0][0]);
  glUniform3fv(fog_loc(prog, "fog_lamp_scatter"), lamps->count, &u.intensity[0][0]);
  fog_lamp_uniforms unscaled;
  fog_lamps_pack(lamps, cam->position, 1.0, &unscaled);
  glUniform3fv(fog_loc(prog, "fog_lamp_intensity"), lamps->count, &unscaled.intensity[0][0]);
  glUniform4fv(fog_loc(prog, "fog_lamp_axis"), lamps->count, &u.axis[0][0]);
  glUniform3fv(fog_loc(prog, "fog_lamp_cone"), lamps->count, &u.cone[0][0]);
  glUniform1i(fog_loc(prog, "fog_lamp_angle_pieces"), lamps->method.angle_pieces);
  glUniform1i(fog_loc(prog, "fog_lamp_span_pieces"), lamps->method.span_pieces);
  glUniform1i(fog_loc(prog, "fog_lamp_depth_steps"), lamps->method.depth_steps);
  glUniform1i(fog_loc(prog, "fog_lamp_shadow_steps"), lamps->method.shadow_steps);
  glUniform1i(fog_loc(prog, "fog_lamp_march_steps"), lamps->method.march_steps);
  if (!fog_pass_has_lamp_shadows(params)) return;
  const lamp_shadow_maps *maps = params->lamp_shadows;
  const lamp_shadow_uniforms shadow = lamp_shadow_maps_uniforms(maps);
  bind_sampler(prog, "lamp_shadow_map", UNIT_LAMP_SHADOWS, GL_TEXTURE_CUBE_MAP_ARRAY,
               maps->texture);
  glUniform1fv(fog_loc(prog, "lamp_shadow_inv_far"), FOG_MAX_LAMPS, shadow.inv_far);
  glUniform1f(fog_loc(prog, "lamp_shadow_slack"), shadow.slack);
  glUniform1f(fog_loc(prog, "lamp_shadow_lift"), shadow.lift);
}

/* Uniforms every model uses (camera, blend, model selection), the surface textures, and
 * the full-screen triangle. */
static int fog_pass_common_and_draw(const fog_pass *pass, GLuint prog, const camera *cam,
                                    const fog_pass_params *params, GLuint surface_colour,
                                    GLuint surface_distance, int width, int height,
                                    int viewport_width, int viewport_height, fog_error *err) {
  const double *c = cam->position;
  glUniform1f(fog_loc(prog, "fog_model_extinction"), (float)params->model_extinction);
  glUniform1f(fog_loc(prog, "fog_model_y0"), (float)(params->model_y0 - c[1]));
  glUniform1f(fog_loc(prog, "fog_model_scale_height"),
              (float)(params->model_scale_height > 0 ? params->model_scale_height : 1.0));
  glUniform1f(fog_loc(prog, "fog_model_start"), (float)params->model_fog_start);
  glUniform1f(fog_loc(prog, "fog_model_end"), (float)params->model_fog_end);
  double right[3], up[3], forward[3];
  camera_basis(cam, width, height, right, up, forward);
  glUniform3d(fog_loc(prog, "fog_camera_right"), right[0], right[1], right[2]);
  glUniform3d(fog_loc(prog, "fog_camera_up"), up[0], up[1], up[2]);
  glUniform3d(fog_loc(prog, "fog_camera_forward"), forward[0], forward[1], forward[2]);
  glUniform2f(fog_loc(prog, "fog_viewport"), (float)width, (float)height);
  glUniform3f(fog_loc(prog, "fog_colour"), params->fog_colour[0], params->fog_colour[1],
              params->fog_colour[2]);
  const fog_sun *sun = &params->sun;
  glUniform3f(fog_loc(prog, "fog_sun_direction"), (float)sun->direction[0],
              (float)sun->direction[1], (float)sun->direction[2]);
  const double scatter = sun->albedo * fog_sun_above_horizon(sun->direction);
  glUniform3f(fog_loc(prog, "fog_sun_scatter"), (float)(scatter * sun->radiance[0]),
              (float)(scatter * sun->radiance[1]), (float)(scatter * sun->radiance[2]));
  glUniform1f(fog_loc(prog, "fog_phase_g"), (float)sun->phase_g);
  fog_pass_sun_shadow_uniforms(pass, prog, cam, params);
  if (fog_pass_has_lamps(params) || fog_pass_has_surface_lamps(params))
    fog_pass_lamp_uniforms(prog, cam, params);
  bind_sampler(prog, "fog_surface_colour", UNIT_SURFACE_COLOUR, GL_TEXTURE_2D, surface_colour);
  bind_sampler(prog, "fog_surface_distance", UNIT_SURFACE_DISTANCE, GL_TEXTURE_2D,
               surface_distance);

  glViewport(0, 0, viewport_width, viewport_height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindVertexArray(gl_util_empty_vao());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glActiveTexture(GL_TEXTURE0);
  return gl_util_check("fog pass: draw", err);
}

/* FOG_MODEL_VOLUME's grid: the 3D texture on a unit of its own, the camera's index position in double rounded once, the matrix
 * that maps directions. */
static void fog_pass_volume_uniforms(const fog_pass *pass, GLuint prog, const camera *cam,
                                     const fog_pass_params *params) {
  const volume_grid_desc *g = &pass->grid3d_place;
  double u[3];
  float m[9];
  volume_grid_index_of(g, cam->position, u);
  volume_grid_gl_matrix(g, m);
  bind_sampler(prog, "fog_grid3d", UNIT_GRID3D, GL_TEXTURE_3D, pass->grid3d);
  glUniformMatrix3fv(fog_loc(prog, "fog_grid3d_index_from_world"), 1, GL_FALSE, m);
  glUniform3f(fog_loc(prog, "fog_grid3d_camera_index"), (float)u[0], (float)u[1], (float)u[2]);

  glUniform3f(fog_loc(prog, "fog_grid3d_dims"), (float)g->dim[0], (float)g->dim[1],
              (float)g->dim[2]);
  glUniform1f(fog_loc(prog, "fog_grid3d_step"), (float)params->model_grid3d_step);
  bind_sampler(prog, "fog_grid3d_occupancy", UNIT_GRID3D_OCCUPANCY, GL_TEXTURE_3D,
               pass->grid3d_occupancy);
  glUniform3i(fog_loc(prog, "fog_grid3d_bricks"), pass->grid3d_bricks[0], pass->grid3d_bricks[1],
              pass->grid3d_bricks[2]);
  glUniform1f(fog_loc(prog, "fog_skip_below"),
              params->walk.skip == FOG_SKIP_BELOW ? params->walk.skip_below : 0.0f);
}

/* A buffer texture over `bytes` of data in format (created on first use, refilled). */
static void buffer_texture_fill(GLuint *buffer, GLuint *texture, GLenum format, const void *data,
                                size_t bytes) {
  if (!*buffer) glGenBuffers(1, buffer);
  if (!*texture) glGenTextures(1, texture);
  glBindBuffer(GL_TEXTURE_BUFFER, *buffer);
  glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)(bytes ? bytes : 16), data, GL_STREAM_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  glBindTexture(GL_TEXTURE_BUFFER, *texture);
  glTexBuffer(GL_TEXTURE_BUFFER, format, *buffer);
}

static int fog_pass_check_loops(const fog_pass *pass, const fog_pass_params *params,
                                int tile_gaussians, fog_error *err);

/* FOG_MODEL_RBF's Gaussians (fog_models.glsl): per Gaussian two texels, the centre relative
 * to the camera (subtracted in double) with 1/radius, and the density; and per screen tile
 * of the width x height image the list of those its rays can see (render/fog_rbf_tiles.h). */
static int fog_pass_rbf_uniforms(fog_pass *pass, GLuint prog, const camera *cam,
                                 const fog_pass_params *params, int width, int height,
                                 fog_error *err) {
  const int n = params->model_rbf_count;
  if (n > pass->rbf_scratch_count) {
    float *more = realloc(pass->rbf_scratch, (size_t)n * 8 * sizeof(float));
    if (!more) {
      fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "fog pass: out of memory (%d RBFs)", n);
      return 1;
    }
    pass->rbf_scratch = more, pass->rbf_scratch_count = n;
  }
  for (int i = 0; i < n; i++) {
    const fog_rbf *g = &params->model_rbfs[i];
    float *texels = pass->rbf_scratch + 8 * (size_t)i;
    for (int a = 0; a < 3; a++) texels[a] = (float)(g->centre[a] - cam->position[a]);
    texels[3] = (float)(1.0 / g->radius);
    /* y: its cull radius (< 0: too faint to reach the bound), the light span's (fog_light.glsl) */
    texels[4] = (float)g->density, texels[5] = (float)fog_rbf_cull_radius(g, n);
    texels[6] = texels[7] = 0.0f;
  }
  if (fog_rbf_tiles_build(&pass->rbf_tiles, cam, width, height, params->model_rbfs, n, err))
    return 1;
  const fog_rbf_tiles *t = &pass->rbf_tiles;
  uint32_t most = 0; /* the longest tile list: a pixel's loops over its Gaussians */
  for (int k = 0; k < t->tiles_x * t->tiles_y; k++)
    if (t->ranges[2 * k + 1] > most) most = t->ranges[2 * k + 1];
  if (fog_pass_check_loops(pass, params, (int)most, err)) return 1;
  /* GL clamps a buffer texture to its limit and a fetch past it reads 0 (Gaussian 0, over
   * and over, for the lists past it): refused. 3000 puffs at 15360 x 8640 (3840 x 2160,
   * supersample 4) list 147M, llvmpipe takes 134M. */
  if (t->index_count > (size_t)pass->max_texture_buffer_size)
    return fog_fail(err, FOG_ERR_GRAPHICS, /* not UNSUPPORTED: callers read that as lamps */
                    "fog pass: the %d Gaussians' tile lists hold %zu entries at %dx%d, more "
                    "than this renderer's buffer texture takes (%d): fewer Gaussians, or a "
                    "smaller image or supersample", n, t->index_count, width, height,
                    (int)pass->max_texture_buffer_size);
  buffer_texture_fill(&pass->rbf_buffer, &pass->rbf_texture, GL_RGBA32F, pass->rbf_scratch,
                      (size_t)n * 8 * sizeof(float));
  buffer_texture_fill(&pass->rbf_index_buffer, &pass->rbf_index_texture, GL_R32UI, t->indices,
                      t->index_count * sizeof(uint32_t));
  if (!pass->rbf_ranges) glGenTextures(1, &pass->rbf_ranges);
  glBindTexture(GL_TEXTURE_2D, pass->rbf_ranges);
  if (pass->rbf_ranges_width != t->tiles_x || pass->rbf_ranges_height != t->tiles_y) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32UI, t->tiles_x, t->tiles_y, 0, GL_RG_INTEGER,
                 GL_UNSIGNED_INT, t->ranges);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    pass->rbf_ranges_width = t->tiles_x, pass->rbf_ranges_height = t->tiles_y;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t->tiles_x, t->tiles_y, GL_RG_INTEGER,
                    GL_UNSIGNED_INT, t->ranges);
  }
  glUniform1i(fog_loc(prog, "fog_rbf_count"), n);
  glUniform1i(fog_loc(prog, "fog_rbf_tile_size"), FOG_RBF_TILE_SIZE);
  bind_sampler(prog, "fog_rbf_data", UNIT_RBF_DATA, GL_TEXTURE_BUFFER, pass->rbf_texture);
  bind_sampler(prog, "fog_rbf_indices", UNIT_RBF_INDICES, GL_TEXTURE_BUFFER,
               pass->rbf_index_texture);
  bind_sampler(prog, "fog_rbf_tiles", UNIT_RBF_TILES, GL_TEXTURE_2D, pass->rbf_ranges);
  return gl_util_check("fog pass: RBF tiles", err);
}

/* Quadric volumes beside another model's fog (fog_pass_params.model_quadrics). */
static bool fog_pass_quadrics_beside(const fog_pass_params *p) {
  return p->model != FOG_MODEL_QUADRIC && p->model_quadric_count > 0;
}

/* Noise inside the quadric volumes: drawn with the octaves (fog_pass_check_model refuses
 * noise without them, or beside the fogmap). */
static bool fog_pass_quadric_noise(const fog_pass_params *p) {
  return p->model_perlin && p->model != FOG_MODEL_FOGMAP &&
         (p->model == FOG_MODEL_QUADRIC || fog_pass_quadrics_beside(p)) &&
         fog_quadric_noisy(p->model_quadrics, p->model_quadric_count);
}

/* The quadric volumes camera-relative (fog_models.glsl), of FOG_MODEL_QUADRIC or beside
 * another model: Q(camera + p) = p.(M p) + 2 g.p + c0 with g = M camera + l and c0 =
 * Q(camera), in double (the shader keeps M, g and c0 in double). */
static void fog_pass_quadric_uniforms(GLuint prog, const camera *cam,
                                      const fog_pass_params *params) {
  double diag[FOG_MAX_QUADRICS][3], off[FOG_MAX_QUADRICS][3];
  float density[FOG_MAX_QUADRICS], edge[FOG_MAX_QUADRICS], noise[FOG_MAX_QUADRICS];
  float lo[FOG_MAX_QUADRICS][3], hi[FOG_MAX_QUADRICS][3];
  double grad_c0[FOG_MAX_QUADRICS][4];
  const double *o = cam->position;
  const int n = params->model_quadric_count;
  double union_lo[3], union_hi[3];
  if (!fog_quadric_bounds(params->model_quadrics, n, union_lo, union_hi))
    for (int a = 0; a < 3; a++) union_lo[a] = union_hi[a] = o[a];
  for (int i = 0; i < n; i++) {
    const fog_quadric *v = &params->model_quadrics[i];
    double m[3][3], l[3];
    fog_quadric_matrix(v, m, l);
    for (int r = 0; r < 3; r++) {
      grad_c0[i][r] = m[r][0] * o[0] + m[r][1] * o[1] + m[r][2] * o[2] + l[r];
      diag[i][r] = m[r][r];
      lo[i][r] = (float)(v->lo[r] - o[r]);
      hi[i][r] = (float)(v->hi[r] - o[r]);
    }

    grad_c0[i][3] = fog_quadric_value(v, o);
    off[i][0] = m[0][1], off[i][1] = m[1][2], off[i][2] = m[0][2];
    density[i] = (float)v->density;
    edge[i] = (float)v->edge;
    /* without octaves (fog_pass_check_model refuses that) the volume stays homogeneous */
    noise[i] = params->model_perlin ? (float)v->noise : 0.0f;
  }
  glUniform1i(fog_loc(prog, "fog_quadric_count"), n);
  /* the noise reads the octaves' sampler: it must name its own unit even when unused */
  glUniform1i(fog_loc(prog, "fog_perlin_texels"), UNIT_PERLIN);
  if (n > 0) {
    glUniform3dv(fog_loc(prog, "fog_quadric_diag"), n, &diag[0][0]);
    glUniform3dv(fog_loc(prog, "fog_quadric_off"), n, &off[0][0]);
    glUniform1fv(fog_loc(prog, "fog_quadric_density"), n, density);
    glUniform1fv(fog_loc(prog, "fog_quadric_edge"), n, edge);
    glUniform1fv(fog_loc(prog, "fog_quadric_noise"), n, noise);
    glUniform4dv(fog_loc(prog, "fog_quadric_grad_c0"), n, &grad_c0[0][0]);
    glUniform3fv(fog_loc(prog, "fog_quadric_lo"), n, &lo[0][0]);
    glUniform3fv(fog_loc(prog, "fog_quadric_hi"), n, &hi[0][0]);
  }
  glUniform3f(fog_loc(prog, "fog_quadric_union_lo"), (float)(union_lo[0] - o[0]),
              (float)(union_lo[1] - o[1]), (float)(union_lo[2] - o[2]));
  glUniform3f(fog_loc(prog, "fog_quadric_union_hi"), (float)(union_hi[0] - o[0]),
              (float)(union_hi[1] - o[1]), (float)(union_hi[2] - o[2]));
}

/* The analytic models need no grids: only the camera and their parameters. */
/* The walk settings' choice for grids with this share of empty blocks or bricks. */
/* FOG_MODEL_PERLIN: each octave's texel position at the camera, its drift included, in
 * double and wrapped into [0, size) (the shader adds camera-relative offsets in float);
 * the box camera-relative. */
static void fog_pass_perlin_uniforms(const fog_pass *pass, GLuint prog, const camera *cam,
                                     const fog_pass_params *params) {
  const fog_perlin *perlin = params->model_perlin;
  const double *c = cam->position;
  const int n = perlin->desc.size;
  float scale[FOG_PERLIN_MAX_OCTAVES] = {0}, origin[FOG_PERLIN_MAX_OCTAVES][3] = {{0}};
  for (int i = 0; i < perlin->desc.octaves; i++) {
    double s = fog_perlin_octave_scale(perlin, i);
    scale[i] = (float)s;
    for (int a = 0; a < 3; a++) {
      double u = fmod((c[a] - perlin->desc.wind[i][a] * params->model_time) * s, (double)n);
      origin[i][a] = (float)(u < 0 ? u + n : u);
    }
  }
  bind_sampler(prog, "fog_perlin_texels", UNIT_PERLIN, GL_TEXTURE_3D, pass->perlin_texture);
  glUniform1i(fog_loc(prog, "fog_perlin_octaves"), perlin->desc.octaves);
  glUniform1i(fog_loc(prog, "fog_perlin_size"), n);
  glUniform1fv(fog_loc(prog, "fog_perlin_scale"), FOG_PERLIN_MAX_OCTAVES, scale);
  glUniform3fv(fog_loc(prog, "fog_perlin_camera"), FOG_PERLIN_MAX_OCTAVES, &origin[0][0]);
  const double *lo = perlin->desc.lo, *hi = perlin->desc.hi;
  glUniform3f(fog_loc(prog, "fog_perlin_lo"), (float)(lo[0] - c[0]), (float)(lo[1] - c[1]),
              (float)(lo[2] - c[2]));
  glUniform3f(fog_loc(prog, "fog_perlin_hi"), (float)(hi[0] - c[0]), (float)(hi[1] - c[1]),
              (float)(hi[2] - c[2]));
  glUniform1i(fog_loc(prog, "fog_perlin_paper"),
              params->model_perlin_integral == FOG_PERLIN_PAPER);
  glUniform1f(fog_loc(prog, "fog_perlin_mean"), (float)perlin->mean_turbulence);
}

static int fog_pass_skips_share(const fog_pass_params *params, double empty_share) {
  if (params->walk.skip == FOG_SKIP_NONE) return 0;
  return params->walk.skip == FOG_SKIP_BELOW || empty_share >= FOG_SKIP_MIN_EMPTY_SHARE;
}

/* The analytic and volume models' uniforms for prog (in use). */
static int fog_pass_analytic_uniforms(fog_pass *pass, GLuint prog, const camera *cam,
                                      const fog_pass_params *params, int width, int height,
                                      fog_error *err) {
  glUniform1i(fog_loc(prog, "fog_march_steps"), params->march_steps);
  glUniform1i(fog_loc(prog, "fog_march_jitter"), params->march_jitter != 0);
  glUniform1ui(fog_loc(prog, "fog_frame"), params->frame);
  /* The sampler array must still name distinct units of the right type. */
  GLint units[FOG_PASS_MAX_GRIDS];
  for (int k = 0; k < FOG_PASS_MAX_GRIDS; k++) units[k] = UNIT_GRIDS + k;
  glUniform1iv(fog_loc(prog, "fog_grids"), FOG_PASS_MAX_GRIDS, units);
  if (params->model == FOG_MODEL_VOLUME) fog_pass_volume_uniforms(pass, prog, cam, params);
  if (params->model == FOG_MODEL_RBF &&
      fog_pass_rbf_uniforms(pass, prog, cam, params, width, height, err))
    return 1;
  if (params->model == FOG_MODEL_QUADRIC || fog_pass_quadrics_beside(params))
    fog_pass_quadric_uniforms(prog, cam, params);
  /* the Perlin fog's octaves, or the turbulence inside quadric volumes with noise */
  if (params->model_perlin) fog_pass_perlin_uniforms(pass, prog, cam, params);
  return 0;
}

/* The fogmap draw's slots: slot `first` shown as slot 0, J levels over `slots` slots, the
 * slots the LOD method reads (fog_pass_check_fogmap). */
typedef struct fogmap_slots {
  int first, J, slots;
  bool reads[FOG_PASS_MAX_GRIDS];
} fogmap_slots;

static int fog_pass_fogmap_uniforms(fog_pass *pass, GLuint prog, const camera *cam,
                                    const fog_pass_params *params, int first, int J, int slots,
                                    const bool reads[FOG_PASS_MAX_GRIDS], fog_error *err);

/* Any model's uniforms for prog (made current): fm for the fogmap. */
static int fog_pass_model_uniforms(fog_pass *pass, GLuint prog, const camera *cam,
                                   const fog_pass_params *params, const fogmap_slots *fm, int width,
                                   int height, fog_error *err) {
  glUseProgram(prog);
  if (params->model == FOG_MODEL_FOGMAP) {
    if (fog_pass_quadrics_beside(params)) fog_pass_quadric_uniforms(prog, cam, params);
    return fog_pass_fogmap_uniforms(pass, prog, cam, params, fm->first, fm->J, fm->slots,
                                    fm->reads, err);
  }
  return fog_pass_analytic_uniforms(pass, prog, cam, params, width, height, err);
}

/* The froxel grid's texture and framebuffer, (re)made when its size changes. */
static int fog_pass_froxel_fit(fog_pass *pass, const fog_froxel_grid *g, fog_error *err) {
  if (pass->froxel_volume && pass->froxel_size[0] == g->columns &&
      pass->froxel_size[1] == g->rows && pass->froxel_size[2] == g->slices)
    return 0;
  if (!pass->froxel_volume) glGenTextures(1, &pass->froxel_volume);
  glBindTexture(GL_TEXTURE_3D, pass->froxel_volume);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA32F, g->columns, g->rows, g->slices, 0, GL_RGBA,
               GL_FLOAT, NULL);
  gl_util_set_sampling(GL_TEXTURE_3D,
                       &(gl_sampling){.filter = GL_LINEAR,
                                      .wrap = {GL_CLAMP_TO_EDGE, GL_CLAMP_TO_EDGE,
                                               GL_CLAMP_TO_EDGE}});
  glBindTexture(GL_TEXTURE_3D, 0);
  GLint caller = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &caller);
  if (!pass->froxel_framebuffer) glGenFramebuffers(1, &pass->froxel_framebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, pass->froxel_framebuffer);
  glFramebufferParameteri(GL_DRAW_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, g->columns);
  glFramebufferParameteri(GL_DRAW_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, g->rows);
  GLenum status = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)caller);
  pass->froxel_size[0] = g->columns, pass->froxel_size[1] = g->rows,
  pass->froxel_size[2] = g->slices;
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fog_fail(err, FOG_ERR_GRAPHICS, "fog pass: froxel framebuffer incomplete (status %#x)",
             (unsigned)status);
    return 1;
  }
  return gl_util_check("fog pass: froxel grid", err);
}

static void fog_pass_froxel_uniforms(GLuint prog, const fog_froxel_grid *g) {
  glUniform3i(fog_loc(prog, "fog_froxel_size"), g->columns, g->rows, g->slices);
  glUniform1f(fog_loc(prog, "fog_froxel_near"), (float)g->near_distance);
  glUniform1f(fog_loc(prog, "fog_froxel_far"), (float)g->far_distance);
}

/* FOG_INTEGRATOR_FROXEL: the fill (one fragment per column of the grid, its slices written
 * with imageStore) into an attachment-less framebuffer, then the lookup at full resolution
 * into the caller's. `variant` holds the model's settings; lamps are not carried. */
static int fog_pass_draw_froxel(fog_pass *pass, const fog_pass_variant *variant, const camera *cam,
                                const fog_pass_params *params, const fogmap_slots *fm,
                                GLuint surface_colour, GLuint surface_distance, int width,
                                int height, fog_error *err) {
  const fog_froxel_grid *g = &params->froxel;
  fog_pass_variant fill = *variant, lookup = *variant;
  fill.quadrics_beside = lookup.quadrics_beside = fog_pass_quadrics_beside(params);
  fill.quadric_noise = lookup.quadric_noise = fog_pass_quadric_noise(params);
  fill.integrator = lookup.integrator = FOG_INTEGRATOR_EXACT;
  fill.reduced = lookup.reduced = 1;
  fill.lamps = lookup.lamps = fill.lamp_integral = lookup.lamp_integral = 0;
  fill.surface_sun = fill.surface_lamps = 0;
  fill.froxel = 1, lookup.froxel = 2;
  fill.shadow_nodes = lookup.shadow_nodes = params->shadow_nodes;
  fill.shaft_samples = lookup.shaft_samples = params->shafts ? params->shaft_samples : 1;
  lookup.lamp_shadows = fog_pass_has_lamp_shadows(params); /* the surfaces' lamp weights */
  GLuint fill_prog = fog_pass_variant_program(pass, &fill, err);
  GLuint lookup_prog = fill_prog ? fog_pass_variant_program(pass, &lookup, err) : 0;
  if (!lookup_prog || fog_pass_froxel_fit(pass, g, err)) return 1;
  GLint caller = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &caller);
  if (fog_pass_model_uniforms(pass, lookup_prog, cam, params, fm, width, height, err) ||
      fog_pass_model_uniforms(pass, fill_prog, cam, params, fm, width, height, err))
    return 1;
  fog_pass_froxel_uniforms(fill_prog, g);
  glBindImageTexture(0, pass->froxel_volume, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glUniform1i(fog_loc(fill_prog, "fog_froxel_image"), 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, pass->froxel_framebuffer);
  int failed = fog_pass_common_and_draw(pass, fill_prog, cam, params, surface_colour,
                                        surface_distance, width, height, g->columns, g->rows,
                                        err);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)caller);
  if (failed) return 1;
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glUseProgram(lookup_prog);
  fog_pass_froxel_uniforms(lookup_prog, g);
  bind_sampler(lookup_prog, "fog_froxel_volume", UNIT_FROXEL, GL_TEXTURE_3D, pass->froxel_volume);
  return fog_pass_common_and_draw(pass, lookup_prog, cam, params, surface_colour,
                                  surface_distance, width, height, width, height, err);
}

static int fog_pass_draw_variant(fog_pass *pass, fog_pass_variant variant, const camera *cam,
                                 const fog_pass_params *params, const fogmap_slots *fm, int divisor,
                                 GLuint surface_colour, GLuint surface_distance, int width,
                                 int height, fog_error *err);

static int fog_pass_draw_analytic(fog_pass *pass, const camera *cam, const fog_pass_params *params,
                                  GLuint surface_colour, GLuint surface_distance, int width,
                                  int height, int divisor, fog_error *err) {
  bool march = params->integrator == FOG_INTEGRATOR_MARCH;
  bool hardware = params->model == FOG_MODEL_VOLUME && params->fetch == FOG_FETCH_HARDWARE;
  const fog_pass_variant variant = {.fetch_hardware = hardware, .integrator = march,
                                    .degree = 1, .single_grid = 1, .model = params->model,
                                    .reduced = 1, .sun_shadow = (int)params->self_shadow,
                                    .surface_sun = params->surface_sun != 0,
                                    .shafts = params->shafts != NULL,
                                    .skip = params->model == FOG_MODEL_VOLUME && !march &&
                                            fog_pass_skips_share(params, pass->grid3d_empty_share),
                                    .lamps = fog_pass_has_lamps(params),
                                    .lamp_integral = fog_pass_has_lamps(params)
                                                         ? (int)params->lamps.method.integral
                                                         : 0,
                                    .surface_lamps = fog_pass_has_surface_lamps(params)};
  if (params->integrator == FOG_INTEGRATOR_FROXEL)
    return fog_pass_draw_froxel(pass, &variant, cam, params, NULL, surface_colour,
                                surface_distance, width, height, err);
  return fog_pass_draw_variant(pass, variant, cam, params, NULL, divisor, surface_colour,
                               surface_distance, width, height, err);
}

/* resolution_divisor > 1, before the reduced draw: the reduced target (reallocated only when
 * the size changes) bound, the caller's framebuffer remembered. */
static int fog_pass_begin_reduced(fog_pass *pass, int divisor, int width, int height, bool lamps,
                                  GLint *caller_framebuffer, fog_error *err) {
  int w = (width + divisor - 1) / divisor, h = (height + divisor - 1) / divisor;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, caller_framebuffer);
  if (pass->reduced.framebuffer && (pass->reduced.width != w || pass->reduced.height != h)) {
    gl_target_destroy(&pass->reduced);
    memset(&pass->reduced, 0, sizeof pass->reduced);
  }
  if (!pass->reduced.framebuffer) {
    /* gl_target_create leaves framebuffer 0 bound for reading too: keep the caller's. */
    GLint caller_read = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &caller_read);
    /* 0: depth, distance, K there, T_s mean; 2: the lamps' in-scatter (1 unused: the
     * shader's transmittance output) */
    int failed = gl_target_create(&pass->reduced,
                                  &(gl_target_desc){.width = w, .height = h,
                                                    .color_formats = {GL_RGBA32F, GL_R32F,
                                                                      GL_RGBA32F}},
                                  err);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)caller_read);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)*caller_framebuffer);
    if (failed) return 1;
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, pass->reduced.framebuffer);
  /* the lamps' attachment only with lamps: an RGBA32F write a sample is not free */
  static const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_COLOR_ATTACHMENT2};
  glDrawBuffers(lamps ? 3 : 1, buffers);
  return 0;
}

/* After the reduced draw: back to the caller's framebuffer; the upsampling variant (its
 * fogmap uniforms already set) blends at full resolution. */
static int fog_pass_finish_reduced(fog_pass *pass, GLuint prog, const camera *cam,
                                   const fog_pass_params *params, int divisor,
                                   GLint caller_framebuffer, GLuint surface_colour,
                                   GLuint surface_distance, int width, int height, fog_error *err) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)caller_framebuffer);
  glUseProgram(prog);
  bind_sampler(prog, "fog_reduced", UNIT_REDUCED, GL_TEXTURE_2D, pass->reduced.color[0]);
  if (fog_pass_has_lamps(params))
    bind_sampler(prog, "fog_reduced_lamps", UNIT_REDUCED_LAMPS, GL_TEXTURE_2D,
                 pass->reduced.color[2]);
  glUniform1i(fog_loc(prog, "fog_divisor"), divisor);
  return fog_pass_common_and_draw(pass, prog, cam, params, surface_colour, surface_distance, width,
                                  height, width, height, err);
}

/* Draws `variant` (any model; fm for the fogmap) at full resolution, or for divisor > 1 its
 * reduced pass and then the same settings' upsampling variant (fog_pass_fs.glsl,
 * FOG_UPSAMPLE), which needs the same uniforms: it walks the pixels no reduced sample
 * matches. */
static int fog_pass_draw_variant(fog_pass *pass, fog_pass_variant variant, const camera *cam,
                                 const fog_pass_params *params, const fogmap_slots *fm, int divisor,
                                 GLuint surface_colour, GLuint surface_distance, int width,
                                 int height, fog_error *err) {
  variant.reduced = divisor > 1 ? divisor : 1;
  variant.shadow_nodes = params->shadow_nodes;
  variant.shaft_samples = params->shafts ? params->shaft_samples : 1;
  variant.lamp_shadows = fog_pass_has_lamp_shadows(params);
  variant.lamp_spots = fog_lamps_have_spot(&params->lamps);
  variant.quadrics_beside = fog_pass_quadrics_beside(params);
  variant.quadric_noise = fog_pass_quadric_noise(params);
  variant.shadow_pieces = (params->model == FOG_MODEL_PERLIN || params->model == FOG_MODEL_VOLUME ||
                           params->model == FOG_MODEL_FOGMAP) &&
                          params->shadow_pieces && !variant.quadrics_beside;
  GLuint walk_prog = fog_pass_variant_program(pass, &variant, err);
  if (!walk_prog) return 1;
  GLuint programs[2] = {walk_prog, 0};
  if (divisor > 1) {
    fog_pass_variant upsample = variant;
    upsample.reduced = 1;
    upsample.upsample = 1;
    programs[1] = fog_pass_variant_program(pass, &upsample, err);
    if (!programs[1]) return 1;
  }
  for (int pi = 0; pi < 2 && programs[pi]; pi++)
    if (fog_pass_model_uniforms(pass, programs[pi], cam, params, fm, width, height, err))
      return 1;
  glUseProgram(walk_prog);
  if (divisor == 1)
    return fog_pass_common_and_draw(pass, walk_prog, cam, params, surface_colour, surface_distance,
                                    width, height, width, height, err);
  GLint caller = 0;
  if (fog_pass_begin_reduced(pass, divisor, width, height, variant.lamps, &caller, err))
    return 1;
  if (fog_pass_common_and_draw(pass, walk_prog, cam, params, surface_colour, surface_distance,
                               width, height, pass->reduced.width, pass->reduced.height, err)) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)caller);
    return 1;
  }
  return fog_pass_finish_reduced(pass, programs[1], cam, params, divisor, caller,
                                 surface_colour, surface_distance, width, height, err);
}

/* llvmpipe ends all of a shader's loops past its cap (docs/platform.md) and the pixel comes
 * out wrong without an error: a draw whose loops' bound (the lamps', the view ray's with up
 * to tile_gaussians Gaussians a pixel) passes it less FOG_PASS_LOOP_RESERVE is refused. */
static int fog_pass_check_loops(const fog_pass *pass, const fog_pass_params *params,
                                int tile_gaussians, fog_error *err) {
  static const char *const integral_names[] = {"angle", "fogshop", "march"};
  const double lamps = fog_pass_lamp_loop_bound(params),
               view = fog_pass_view_loop_bound(params, tile_gaussians);
  if (lamps + view <= fog_pass_loops_allowed(pass)) return 0;
  /* whether the draw would fit without the turbulence's walks (then the hint says what
   * shortens them; else the lamps or the sun's steps must go down too) */
  const bool turbulence_over =
      lamps + view - fog_pass_turbulence_loop_bound(params) <= fog_pass_loops_allowed(pass);
  const fog_lamp_method *m = &params->lamps.method;
  char gaussians[64] = "", sun[64] = "no sun's mean", lamp_text[160] = "no lamps";
  if (params->lamps.count > 0)
    snprintf(lamp_text, sizeof lamp_text,
             "%.0f for %d lamp%s (the %s integral: %d + %d pieces, %d shadow steps, %d march "
             "steps)", lamps, params->lamps.count, params->lamps.count == 1 ? "" : "s",
             integral_names[m->integral], m->angle_pieces, m->span_pieces, m->shadow_steps,
             m->march_steps);
  if (params->self_shadow != FOG_SUN_SHADOW_NONE || params->shafts)
    snprintf(sun, sizeof sun, "the sun's mean over %d shadow steps of %d nodes",
             params->shadow_steps, params->shadow_nodes);
  if (params->model == FOG_MODEL_RBF)
    snprintf(gaussians, sizeof gaussians, " (%d Gaussians, up to %d in a screen tile)",
             params->model_rbf_count, tile_gaussians);
  fog_fail(err, FOG_ERR_UNSUPPORTED,
           "fog pass: %s fog%s may run %.0f loop iterations a pixel: %s, and %.0f for the "
           "view ray (%s); this renderer (%s) ends "
           "all of a shader's loops after %ld and would draw them wrong: expected a bound of "
           "at most %ld (fewer lamps, lamp pieces or steps, sun shadow steps%s%s)",
           fog_model_table[params->model].name, gaussians, lamps + view, lamp_text, view, sun,
           (const char *)glGetString(GL_RENDERER), pass->loop_cap,
           (long)fog_pass_loops_allowed(pass),
           params->model == FOG_MODEL_RBF ? ", or fewer Gaussians" : "",
           !turbulence_over ? ""
           : params->model == FOG_MODEL_PERLIN
               ? "; without the turbulence's walks it would fit: a larger perlin_feature, "
                 "fewer perlin_octaves, a smaller fog box, smaller noisy quadric volumes or "
                 "NOISE 0, or for the sun's mean per piece shadow_pieces = off or "
                 "shadow_nodes = 1"
               : "; without the volumes' noise walks it would fit: a larger perlin_feature, "
                 "smaller noisy volumes or NOISE 0");
  return 1;
}

/* The sun's shadow settings and the lamps, before anything is drawn. */
static int fog_pass_check_light(const fog_pass *pass, const fog_pass_params *params,
                                fog_error *err) {
  if ((unsigned)params->self_shadow > FOG_SUN_SHADOW_OPAQUE ||
      ((params->self_shadow != FOG_SUN_SHADOW_NONE || params->shafts) &&
       (params->shadow_steps < 1 || params->shadow_nodes < 1 || params->shadow_nodes > 2)) ||
      (params->shafts &&
       (params->shaft_samples < 1 || params->shaft_samples > FOG_PASS_MAX_SHAFT_SAMPLES)) ||
      (params->self_shadow == FOG_SUN_SHADOW_VOLUME && !pass->sun_shadow)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: self-shadow %d with %d steps of %d nodes, %d shaft samples: expected "
             "a fog_sun_shadow_kind, >= 1 steps of 1 or 2 nodes, 1 to %d shaft samples and, "
             "for the volume, fog_pass_upload_sun_shadow first",
             (int)params->self_shadow, params->shadow_steps, params->shadow_nodes,
             params->shaft_samples, FOG_PASS_MAX_SHAFT_SAMPLES);
    return 1;
  }
  const fog_lamps *lamps = &params->lamps;
  if (lamps->count < 0 || lamps->count > FOG_MAX_LAMPS ||
      (lamps->count > 0 &&
       (lamps->method.angle_pieces < 1 || lamps->method.span_pieces < 0 ||
        lamps->method.shadow_steps < 1 ||
        lamps->method.depth_steps < 1 || lamps->method.depth_steps > FOG_LAMP_MAX_DEPTH_STEPS))) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: %d lamps with %d + %d pieces, %d depth steps, %d shadow steps: expected "
             "0 to %d lamps, >= 1 angle pieces, >= 0 span pieces, >= 1 shadow steps, 1 to %d "
             "depth steps",
             lamps->count, lamps->method.angle_pieces, lamps->method.span_pieces,
             lamps->method.depth_steps, lamps->method.shadow_steps, FOG_MAX_LAMPS,
             FOG_LAMP_MAX_DEPTH_STEPS);
    return 1;
  }
  if (lamps->count > 0 &&
      ((lamps->method.integral == FOG_LAMP_FOGSHOP && params->model != FOG_MODEL_RBF) ||
       (lamps->method.integral == FOG_LAMP_MARCH && lamps->method.march_steps < 1) ||
       (unsigned)lamps->method.integral > FOG_LAMP_MARCH)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: lamp integral %d with model %d, %d march steps: expected FOG_LAMP_ANGLE, "
             "FOG_LAMP_FOGSHOP with FOG_MODEL_RBF, or FOG_LAMP_MARCH with >= 1 steps",
             (int)lamps->method.integral, (int)params->model, lamps->method.march_steps);
    return 1;
  }
  for (int i = 0; i < lamps->count; i++) {
    const fog_lamp *l = &lamps->lamp[i];
    if (!(l->radius > 0) ||
        (l->kind == FOG_LAMP_SPOT && !(l->cos_inner - l->cos_outer >= FOG_SPOT_MIN_COSINE_GAP))) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "fog pass: lamp %d: radius %g, cone cosines %.17g > %.17g: expected radius > 0 "
               "and, for a spot, cos_inner >= cos_outer + %g",
               i, l->radius, l->cos_inner, l->cos_outer, FOG_SPOT_MIN_COSINE_GAP);
      return 1;
    }
  }
  return 0;
}

/* The integrator's settings: marching samples, the froxel grid, the walk's cut-off. */
static int fog_pass_check_integrator(const fog_pass *pass, const fog_pass_params *params,
                                     fog_error *err) {
  if (params->integrator == FOG_INTEGRATOR_MARCH && params->model != FOG_MODEL_VOLUME &&
      params->march_steps < 1) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: marching with %d samples a ray: expected >= 1 (FOG_PASS_MARCH_STEPS "
             "is the usual choice)",
             params->march_steps);
    return 1;
  }
  const fog_froxel_grid *g = &params->froxel;
  if ((unsigned)params->integrator > FOG_INTEGRATOR_FROXEL ||
      (params->integrator == FOG_INTEGRATOR_FROXEL &&
       (g->columns < 1 || g->rows < 1 || g->slices < 1 || g->columns > pass->max_3d_texture_size ||
        g->rows > pass->max_3d_texture_size || g->slices > pass->max_3d_texture_size ||
        !(g->near_distance > 0) || !(g->far_distance > g->near_distance) ||
        !isfinite(g->far_distance)))) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: integrator %d, froxel grid %d x %d x %d from %g to %g: expected an "
             "fog_integrator and, for the froxels, 1..%d cells a side and 0 < near < far",
             (int)params->integrator, g->columns, g->rows, g->slices, g->near_distance,
             g->far_distance, pass->max_3d_texture_size);
    return 1;
  }
  if (!(params->walk.transmittance_cutoff >= 0 && params->walk.transmittance_cutoff < 1)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: transmittance cut-off %g: expected 0 (never stop) or in (0, 1)",
             params->walk.transmittance_cutoff);
    return 1;
  }
  return 0;
}

/* The analytic and volume models' parameters, before anything is drawn. */
static int fog_pass_check_model(const fog_pass *pass, const fog_pass_params *params,
                                fog_error *err) {
  if (fog_pass_check_light(pass, params, err) || fog_pass_check_integrator(pass, params, err))
    return 1;
  if (params->model == FOG_MODEL_PERLIN &&
      (!params->model_perlin || !pass->perlin_texture ||
       pass->perlin_size != params->model_perlin->desc.size ||
       pass->perlin_octaves != params->model_perlin->desc.octaves ||
       !(params->model_scale_height > 0) || !isfinite(params->model_time) ||
       (unsigned)params->model_perlin_integral > FOG_PERLIN_PAPER)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: Perlin fog: expected its octaves uploaded (fog_pass_upload_perlin), a "
             "scale height > 0, a finite time and a fog_perlin_integral");
    return 1;
  }
  if (params->model == FOG_MODEL_HEIGHT && !(params->model_scale_height > 0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: height fog scale height %g: expected > 0",
             params->model_scale_height);
    return 1;
  }
  if (params->model == FOG_MODEL_LINEAR &&
      !(params->model_fog_start >= 0 && params->model_fog_end > params->model_fog_start)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: linear fog from %g to %g: expected 0 <= start < end",
             params->model_fog_start, params->model_fog_end);
    return 1;
  }
  if (params->model == FOG_MODEL_VOLUME &&
      (!pass->grid3d ||
       (params->integrator == FOG_INTEGRATOR_MARCH && !(params->model_grid3d_step > 0)))) {
    fog_fail(
        err, FOG_ERR_INVALID_ARGUMENT, "fog pass: volume model: %s",
        !pass->grid3d ? "no grid uploaded (fog_pass_upload_grid3d)" : "expected a march step > 0");
    return 1;
  }
  if (params->model == FOG_MODEL_RBF) {
    int n = params->model_rbf_count;
    if (n < 0 || n > FOG_MAX_RBFS || (n > 0 && !params->model_rbfs)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: %d RBFs: expected 0..%d (and the array)",
               n, FOG_MAX_RBFS);
      return 1;
    }
    for (int i = 0; i < n; i++)
      if (!(params->model_rbfs[i].radius > 0) || !(params->model_rbfs[i].density >= 0)) {
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "fog pass: RBF %d: radius %g and density %g: expected radius > 0, density >= 0", i,
                 params->model_rbfs[i].radius, params->model_rbfs[i].density);
        return 1;
      }
  }
  if (params->model == FOG_MODEL_QUADRIC || params->model_quadric_count != 0) {
    int n = params->model_quadric_count;
    if (n < 0 || n > FOG_MAX_QUADRICS || (n > 0 && !params->model_quadrics)) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "fog pass: %d quadric volumes: expected 0..%d (and the array)", n, FOG_MAX_QUADRICS);
      return 1;
    }
    const fog_perlin *octaves = params->model_perlin;
    if (fog_quadric_noisy(params->model_quadrics, n) &&
        (params->model == FOG_MODEL_FOGMAP || !octaves || !pass->perlin_texture ||
         pass->perlin_size != octaves->desc.size || pass->perlin_octaves != octaves->desc.octaves ||
         !isfinite(params->model_time))) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
               "fog pass: quadric volumes with noise: expected model quadric or perlin, its "
               "octaves uploaded (fog_pass_upload_perlin) and a finite time");
      return 1;
    }
    for (int i = 0; i < n; i++) {
      const fog_quadric *v = &params->model_quadrics[i];
      bool ok = v->density >= 0 && v->edge >= 0 && v->noise >= 0 && v->noise <= 1;
      for (int a = 0; a < 3; a++) ok = ok && v->lo[a] <= v->hi[a];
      for (int k = 0; k < 10; k++) ok = ok && isfinite(v->q[k]);
      if (!ok) {
        fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
                 "fog pass: quadric volume %d: expected finite coefficients, density >= 0, "
                 "edge >= 0, noise in [0, 1] and a box lo <= hi",
                 i);
        return 1;
      }
    }
  }
  /* the loops' bound against the renderer's cap, once the settings it reads are checked
   * (over RBF fog when the tiles are built: fog_pass_rbf_uniforms) */
  if (params->model != FOG_MODEL_RBF && fog_pass_check_loops(pass, params, 0, err)) return 1;
  return 0;
}

/* The fogmap draw's grids and profile, before anything is drawn: reads[k] tells which slots
 * the LOD method reads (switching A_0..A_J, slots 0..J; the sum of details A_0 and D_1..D_J,
 * slots 0 and J+1..2J, and A_J, slot J, which its light reads), each must have been
 * uploaded. */
static int fog_pass_check_fogmap(const fog_pass *pass, const fog_pass_params *params,
                                 bool reads[FOG_PASS_MAX_GRIDS], fog_error *err) {
  const fog_volume *v = params->volume;
  const int J = params->levels, slots = 2 * J + 1;
  if (!v || J < 0 || slots > FOG_PASS_MAX_GRIDS) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: draw needs a fog volume and 0..%d LOD levels (got %d)", FOG_MAX_LEVELS, J);
    return 1;
  }
  for (int k = 0; k < FOG_PASS_MAX_GRIDS; k++)
    reads[k] = k < slots && ((k == 0) || k == J ||
                             (params->lod_method == FOG_LOD_SWITCH ? k <= J : k > J));
  for (int k = 0; k < slots; k++)
    if (reads[k] && !pass->slots[k].texture) {
      fog_fail(err, FOG_ERR_INVALID_ARGUMENT, "fog pass: grid slot %d (%s) was never uploaded", k,
               k <= J ? "an approximation A_l in slot l" : "a detail D_l in slot J + l");
      return 1;
    }
  if (!(v->cell_size > 0) || !(v->extinction >= 0) || !isfinite(v->cell_size) ||
      !isfinite(v->extinction)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: fog volume cell size %g and extinction %g: expected a cell size > 0 "
             "and an extinction >= 0 (0: no fog), both finite",
             v->cell_size, v->extinction);
    return 1;
  }
  if (params->walk.skip == FOG_SKIP_BELOW && !(params->walk.skip_below >= 0 && isfinite(params->walk.skip_below))) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: skip_below %g: expected a finite bound >= 0 of the fog skipped",
             params->walk.skip_below);
    return 1;
  }
  const fog_profile *p = &v->profile;
  if (p->kind == FOG_PROFILE_BSPLINE &&
      (p->count < 1 || p->count > FOG_PROFILE_MAX_COEFFICIENTS || p->degree < 0 ||
       p->degree > 3 || !(p->spacing > 0))) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: B-spline profile with %d coefficients of degree %d: expected 1..%d "
             "coefficients of degree 0..3 and a positive spacing",
             p->count, p->degree, FOG_PROFILE_MAX_COEFFICIENTS);
    return 1;
  }
  return 0;
}

/* The fogmap's grids (slot `first` shown as slot 0), their camera-relative placement in
 * double (fog_integral.glsl, fog_optical_depth_inside) and the profile, for program prog
 * of a draw with J levels over `slots` slots. */
static int fog_pass_fogmap_uniforms(fog_pass *pass, GLuint prog, const camera *cam,
                                    const fog_pass_params *params, int first, int J, int slots,
                                    const bool reads[FOG_PASS_MAX_GRIDS], fog_error *err) {
  const fog_volume *v = params->volume;
  const fog_profile *p = &v->profile;
  const double *c = cam->position;
  double h = v->cell_size; /* checked > 0 */
  double x0[FOG_PASS_MAX_GRIDS][2], scale[FOG_PASS_MAX_GRIDS];
  GLint size[FOG_PASS_MAX_GRIDS][2], units[FOG_PASS_MAX_GRIDS], blocks[FOG_PASS_MAX_GRIDS][2];
  for (int k = 0; k < FOG_PASS_MAX_GRIDS; k++) {
    const fog_pass_slot *s = &pass->slots[k == 0 ? first : k];
    units[k] = UNIT_GRIDS + k;
    double sp = s->spacing > 0 ? s->spacing : 1.0;
    x0[k][0] = (-(v->origin_x - c[0]) / h - 0.5 - s->origin_u) / sp;
    x0[k][1] = (-(v->origin_z - c[2]) / h - 0.5 - s->origin_v) / sp;
    scale[k] = 1.0 / (h * sp);
    size[k][0] = s->width;
    size[k][1] = s->height;
    blocks[k][0] = s->occupancy_width;
    blocks[k][1] = s->occupancy_height;
    glActiveTexture(GL_TEXTURE0 + UNIT_GRIDS + (GLenum)k);
    glBindTexture(GL_TEXTURE_2D, reads[k] ? s->texture : 0);
  }
  glUniform1iv(fog_loc(prog, "fog_grids"), FOG_PASS_MAX_GRIDS, units);
  /* The cell polynomials: slot `first` alone, or every slot as layers (J > 0). */
  bind_sampler(prog, "fog_cells", UNIT_CELLS, GL_TEXTURE_2D, pass->slots[first].cells);
  bind_sampler(prog, "fog_occupancy", UNIT_OCCUPANCY, GL_TEXTURE_2D,
               pass->slots[first].occupancy);
  glUniform2iv(fog_loc(prog, "fog_occupancy_size"), FOG_PASS_MAX_GRIDS, &blocks[0][0]);
  /* Each grid the walk reads skips on its own. Switching reads one grid at each point of
   * the ray; the sum of details adds J + 1 grids along it (A_0 and D_1..D_J), so each skips
   * below skip_below / (J + 1) and the sum stays within the one bound (fog_pass.h). */
  const float skip_below = params->walk.skip == FOG_SKIP_BELOW ? params->walk.skip_below : 0.0f;
  glUniform1f(fog_loc(prog, "fog_skip_below"),
              J > 0 && params->lod_method == FOG_LOD_SUM_OF_DETAILS ? skip_below / (float)(J + 1)
                                                                   : skip_below);
  if (J > 0) {
    if (fog_pass_update_layers(pass, slots, err)) return 1;
    bind_sampler(prog, "fog_grid_layers", UNIT_GRID_LAYERS, GL_TEXTURE_2D_ARRAY, pass->layers);
    glUniform2f(fog_loc(prog, "fog_grid_layer_size"), (float)pass->layers_width,
                (float)pass->layers_height);
    bind_sampler(prog, "fog_cell_layers", UNIT_CELL_LAYERS, GL_TEXTURE_2D_ARRAY,
                 pass->cell_layers);
    bind_sampler(prog, "fog_occupancy_layers", UNIT_OCCUPANCY_LAYERS, GL_TEXTURE_2D_ARRAY,
                 pass->occupancy_layers);
  }
  /* Approximation slots 0..J are dyadic, u_k = u_{k+1}/2 + c_k (fog_walk_coarser): from
   * u = (A - origin)/spacing, c_k = (origin_{k+1} - origin_k) / spacing_k. */
  float dyadic[FOG_PASS_MAX_GRIDS][2] = {{0}};
  for (int k = 0; k < J; k++) {
    const fog_pass_slot *s = &pass->slots[k], *finer = &pass->slots[k + 1];
    double sp = s->spacing > 0 ? s->spacing : 1.0;
    dyadic[k][0] = (float)((finer->origin_u - s->origin_u) / sp);
    dyadic[k][1] = (float)((finer->origin_v - s->origin_v) / sp);
  }
  glUniform2fv(fog_loc(prog, "fog_grid_dyadic"), FOG_PASS_MAX_GRIDS, &dyadic[0][0]);
  glUniform2dv(fog_loc(prog, "fog_grid_x0"), FOG_PASS_MAX_GRIDS, &x0[0][0]);
  glUniform1dv(fog_loc(prog, "fog_grid_scale"), FOG_PASS_MAX_GRIDS, scale);
  glUniform2iv(fog_loc(prog, "fog_grid_size"), FOG_PASS_MAX_GRIDS, &size[0][0]);
  double lo[3], hi[3];
  fog_volume_box(v, lo, hi);
  glUniform3d(fog_loc(prog, "fog_box_min"), lo[0] - c[0], lo[1] - c[1], lo[2] - c[2]);
  glUniform3d(fog_loc(prog, "fog_box_max"), hi[0] - c[0], hi[1] - c[1], hi[2] - c[2]);
  glUniform1f(fog_loc(prog, "fog_extinction_scale"), (float)v->extinction);
  glUniform1f(fog_loc(prog, "fog_profile_y0"), (float)(p->y0 - c[1]));
  glUniform1f(fog_loc(prog, "fog_profile_scale_height"),
              (float)(p->scale_height > 0 ? p->scale_height : 1.0));
  glUniform1f(fog_loc(prog, "fog_profile_inv_scale_height"),
              (float)(p->scale_height > 0 ? 1.0 / p->scale_height : 1.0));
  const bool bspline = p->kind == FOG_PROFILE_BSPLINE;
  float coefficients[FOG_PROFILE_MAX_COEFFICIENTS];
  for (int k = 0; bspline && k < p->count; k++) coefficients[k] = (float)p->coefficients[k];
  glUniform1i(fog_loc(prog, "fog_profile_count"), bspline ? p->count : 0);
  glUniform1f(fog_loc(prog, "fog_profile_y_start"),
              bspline ? (float)((c[1] - p->origin) / p->spacing) : 0.0f);
  glUniform1f(fog_loc(prog, "fog_profile_inv_spacing"), bspline ? (float)(1.0 / p->spacing) : 0.0f);
  glUniform1d(fog_loc(prog, "fog_profile_y0_d"), p->y0 - c[1]);
  glUniform1d(fog_loc(prog, "fog_profile_y_start_d"), bspline ? (c[1] - p->origin) / p->spacing : 0.0);
  glUniform1d(fog_loc(prog, "fog_profile_inv_spacing_d"), bspline ? 1.0 / p->spacing : 0.0);
  if (bspline) glUniform1fv(fog_loc(prog, "fog_profile_coefficients"), p->count, coefficients);

  glUniform1d(fog_loc(prog, "fog_mu"), J > 0 ? params->mu : 1.0);
  glUniform1i(fog_loc(prog, "fog_march_steps"), params->march_steps);
  glUniform1i(fog_loc(prog, "fog_march_jitter"), params->march_jitter != 0);
  glUniform1ui(fog_loc(prog, "fog_frame"), params->frame);
  return 0;
}

/* Whether the fogmap walk skips empty blocks: FOG_SKIP_BELOW always; FOG_SKIP_EMPTY where
 * the grids it reads have FOG_SKIP_MIN_EMPTY_SHARE of their blocks empty or more (the
 * skipping walk's per-block cost is not repaid by fog without holes); the marcher samples
 * pointwise and has nothing to skip. */
static int fog_pass_skips(const fog_pass *pass, const fog_pass_params *params, int first,
                          const bool reads[FOG_PASS_MAX_GRIDS]) {
  if (params->integrator != FOG_INTEGRATOR_EXACT) return 0;
  double share = 0.0;
  int count = 0;
  for (int k = 0; k < FOG_PASS_MAX_GRIDS; k++) /* slot 0 shows slot `first` */
    if (reads[k]) share += pass->slots[k == 0 ? first : k].empty_share, count++;
  return count > 0 && fog_pass_skips_share(params, share / count);
}

double fog_pass_depth_limit(double transmittance_cutoff) {
  return transmittance_cutoff > 0 ? -log(transmittance_cutoff) : HUGE_VAL;
}

int fog_pass_draw(fog_pass *pass, const camera *cam, const fog_pass_params *params,
                  GLuint surface_colour, GLuint surface_distance, int width, int height,
                  fog_error *err) {
  if (fog_pass_check_model(pass, params, err)) return 1;
  if (!(cam->fov_y > 0 && cam->fov_y < 3.14159265358979323846 && cam->near_plane > 0 &&
        cam->far_plane > cam->near_plane)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: camera fov %g rad, near %g, far %g: expected 0 < fov < pi and "
             "0 < near < far (camera.h's CAMERA_DEFAULT_* where there is no opinion)",
             cam->fov_y, cam->near_plane, cam->far_plane);
    return 1;
  }
  int divisor = params->resolution_divisor > 1 ? params->resolution_divisor : 1;
  if (divisor != 1 && divisor != 2 && divisor != 4) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "fog pass: resolution divisor %d: expected 0 or 1 (full), 2 or 4",
             params->resolution_divisor);
    return 1;
  }
  if (params->model != FOG_MODEL_FOGMAP) return fog_pass_draw_analytic(pass, cam, params,
      surface_colour, surface_distance, width, height, divisor, err);
  bool reads[FOG_PASS_MAX_GRIDS];
  if (fog_pass_check_fogmap(pass, params, reads, err)) return 1;
  int J = params->levels, slots = 2 * J + 1;
  const fog_profile *p = &params->volume->profile;
  /* Switching at mu >= 1 reads A_J alone over the whole ray, at mu <= 0 A_0 alone (so does
   * the sum of details at mu <= 0): draw those as the one-grid variant of that slot, which
   * skips the LOD loop and the array layers (the same integral, bit for bit the draw of that
   * grid alone). */
  int first = 0;
  if (J > 0 && (params->mu <= 0.0 || (params->lod_method == FOG_LOD_SWITCH && params->mu >= 1.0))) {
    first = params->mu <= 0.0 ? 0 : J;
    J = 0;
    slots = 1;
    for (int k = 1; k < FOG_PASS_MAX_GRIDS; k++) reads[k] = false;
  }
  fog_pass_variant variant = {
      .fetch_hardware = params->fetch == FOG_FETCH_HARDWARE,
      .integrator = params->integrator,
      .degree = pass->slots[first].degree,
      .profile_kind = (int)p->kind,
      .profile_degree = p->kind == FOG_PROFILE_BSPLINE ? p->degree : 0,
      .single_grid = J == 0,
      .model = FOG_MODEL_FOGMAP,
      .lod_method = J == 0 ? FOG_LOD_SWITCH : params->lod_method,
      .reduced = divisor > 1 ? divisor : 1,
      .levels = J,
      .sun_shadow = (int)params->self_shadow,
      .surface_sun = params->surface_sun != 0,
      .shafts = params->shafts != NULL,
      .skip = fog_pass_skips(pass, params, first, reads),
      .lamps = fog_pass_has_lamps(params),
      .lamp_integral = fog_pass_has_lamps(params) ? (int)params->lamps.method.integral : 0,
      .surface_lamps = fog_pass_has_surface_lamps(params),
  };
  fogmap_slots fm = {.first = first, .J = J, .slots = slots};
  memcpy(fm.reads, reads, sizeof fm.reads);
  if (params->integrator == FOG_INTEGRATOR_FROXEL)
    return fog_pass_draw_froxel(pass, &variant, cam, params, &fm, surface_colour,
                                surface_distance, width, height, err);
  return fog_pass_draw_variant(pass, variant, cam, params, &fm, divisor, surface_colour,
                               surface_distance, width, height, err);
}

void fog_pass_finish(void) { glFinish(); }
