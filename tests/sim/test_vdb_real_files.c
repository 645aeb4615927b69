/* Every frame of the Blender/Mantaflow caches in ../shared/data/vdb imports: mass = voxel
 * sum × voxel volume (an independent sum over the dense grid, voxel size from the domain
 * box in the README), the fogmap total equals it (≤ 1e-5), the placement matches the
 * scene (domain boxes, half-voxel convention: the plume's emitter sits at x = z = 0), and
 * the ground fog stays near the ground in its profile. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "sim/sim.h"
#include "test_util.h"

typedef struct scene {
  const char *name;
  double dx;                   /* README: domain size / resolution */
  double x0, x1, z0, z1, y0, y1;  /* fogpipe world box: X = x, Y = z (up), Z = -y */
} scene;

static const scene scenes[] = {
    {"plume", 0.0625, -1, 1, -1, 1, 0, 4},
    {"groundfog", 0.09375, -3, 3, -3, 3, 0, 1.5},
};

static double fogmap_mass(const vdb_frame *f) {
  double s = 0;
  for (int n = 0; n < f->map.width * f->map.height; n++) s += f->map.density[n];
  return s * f->fogmap_place.cell_size * f->fogmap_place.cell_size * f->profile.thickness;
}

/* A glob lists one folder: wildcards in its file name find the bake's frames, in a folder
 * name they are refused at once (they made glob walk whole trees), naming the input. */
static void check_globs(void) {
  const char *name_glob = "../shared/data/vdb/plume/data/fluid_data_00*.vdb";
  vdb_sequence seq;
  fog_error err = {0};
  CHECK(vdb_sequence_find(&name_glob, 1, -1, -1, &seq, &err) == 0 && seq.count == 48,
        "%s: %s", name_glob, err.message);
  if (!err.message[0]) vdb_sequence_destroy(&seq);
  const char *folder_globs[] = {"/*/*/*/*.vdb", "../shared/data/vdb/*/data/fluid_data_0001.vdb"};
  for (int i = 0; i < 2; i++) {
    err.message[0] = '\0';
    CHECK(vdb_sequence_find(&folder_globs[i], 1, -1, -1, &seq, &err) != 0 &&
              strstr(err.message, folder_globs[i]) && strstr(err.message, "file name only"),
          "%s: accepted (%s)", folder_globs[i], err.message);
  }
}

int main(void) {
  check_globs();
  for (int s = 0; s < 2; s++) {
    const scene *sc = &scenes[s];
    char pattern[256];
    snprintf(pattern, sizeof pattern, "../shared/data/vdb/%s/data/fluid_data_####.vdb", sc->name);
    const char *inputs[] = {pattern};
    vdb_sequence seq;
    fog_error err = {0};
    if (vdb_sequence_find(inputs, 1, -1, -1, &seq, &err)) {
      CHECK(0, "%s", err.message);
      continue;
    }
    CHECK(seq.count == 48 && seq.missing_count == 0 && seq.frames[0] == 1 &&
              seq.frames[47] == 48,
          "%s: %d frames, %d missing", sc->name, seq.count, seq.missing_count);
    double worst_mass = 0, worst_fogmap = 0;
    for (int i = 0; i < seq.count; i++) {
      vdb_frame f;
      if (vdb_frame_load(seq.paths[i], &(vdb_frame_desc){.keep_grid = 1}, &f, &err)) {
        CHECK(0, "frame %d: %s", seq.frames[i], err.message);
        continue;
      }
      /* independent: Σ voxel values × dx³ */
      double sum = 0;
      const vdb_dense_grid *g = &f.grid;
      for (long n = 0; n < (long)g->dim[0] * g->dim[1] * g->dim[2]; n++) sum += g->values[n];
      const double expected = sum * sc->dx * sc->dx * sc->dx;
      worst_mass = fmax(worst_mass, fabs(f.columns.mass - expected) / expected);
      worst_fogmap = fmax(worst_fogmap, fabs(fogmap_mass(&f) - expected) / expected);
      CHECK(f.world.used_config, "%s frame %d: config not found", sc->name, seq.frames[i]);
      const vdb_fogmap_place *p = &f.fogmap_place;
      CHECK(fabs(p->origin_x - sc->x0) < 1e-5 && fabs(p->origin_z - sc->z0) < 1e-5 &&
                fabs(p->cell_size - sc->dx) < 1e-7 &&
                fabs(p->origin_x + p->width * p->cell_size - sc->x1) < 1e-5 &&
                fabs(p->origin_z + p->height * p->cell_size - sc->z1) < 1e-5,
            "%s frame %d: fogmap at (%g, %g) %dx%d cells of %g", sc->name, seq.frames[i],
            p->origin_x, p->origin_z, p->width, p->height, p->cell_size);
      const double top = f.columns.y_min + f.columns.layers * f.columns.layer_height;
      CHECK(fabs(f.columns.y_min - sc->y0) < 1e-5 && fabs(top - sc->y1) < 1e-5,
            "%s frame %d: layers span [%g, %g]", sc->name, seq.frames[i], f.columns.y_min, top);
      /* degree-1 profile: knots at the layer centres, support half a layer beyond */
      const double h = f.columns.layer_height;
      CHECK(f.profile.count == f.columns.layers && fabs(f.profile.origin - sc->y0 - h / 2) < 1e-6 &&
                fabs(f.profile.y_bottom - (sc->y0 - h / 2)) < 1e-6 &&
                fabs(f.profile.y_top - (sc->y1 + h / 2)) < 1e-6,
            "%s frame %d: profile %d knots from %g, support [%g, %g]", sc->name, seq.frames[i],
            f.profile.count, f.profile.origin, f.profile.y_bottom, f.profile.y_top);
      if (s == 0 && seq.frames[i] == 1) {
        /* the emitter sphere is centred at Blender x = y = 0: the fogmap centroid too */
        double cx = 0, cz = 0, m = 0;
        for (int z = 0; z < f.map.height; z++)
          for (int x = 0; x < f.map.width; x++) {
            const double v = f.map.density[z * f.map.width + x];
            cx += v * (p->origin_x + (x + 0.5) * p->cell_size);
            cz += v * (p->origin_z + (z + 0.5) * p->cell_size);
            m += v;
          }
        CHECK(fabs(cx / m) < 0.01 && fabs(cz / m) < 0.01,
              "plume frame 1: centroid (%.4f, %.4f), expected (0, 0)", cx / m, cz / m);
      }
      if (s == 1 && seq.frames[i] == 48) {
        /* README: ~76 % of the mass in z < ~0.38 m at frame 48 */
        double below = 0, all = 0;
        for (int n = 0; n < 15000; n++) {
          const double y = f.profile.y_bottom + (n + 0.5) * (f.profile.y_top - f.profile.y_bottom) / 15000;
          const double gv = vdb_profile_eval(&f.profile, y);
          all += gv;
          if (y < 0.4) below += gv;
        }
        printf("groundfog frame 48: %.1f %% of the profile below 0.4 m, mass %.6g\n",
               100 * below / all, f.columns.mass);
        CHECK(below / all >= 0.70, "groundfog frame 48: only %.1f %% below 0.4 m",
              100 * below / all);
        CHECK(fabs(all * (f.profile.y_top - f.profile.y_bottom) / 15000 - f.profile.thickness) <
                  1e-4 * f.profile.thickness,
              "profile thickness %g vs its integral", f.profile.thickness);
      }
      vdb_frame_destroy(&f);
    }
    printf("%s: %d frames, worst relative mass error %.3g, fogmap total %.3g\n", sc->name,
           seq.count, worst_mass, worst_fogmap);
    CHECK(worst_mass < 1e-6, "%s: projected mass off by %.3g", sc->name, worst_mass);
    CHECK(worst_fogmap < 1e-5, "%s: fogmap total off by %.3g", sc->name, worst_fogmap);
    vdb_sequence_destroy(&seq);
  }
  return test_finish("test_vdb_real_files");
}
