/* A ray against an axis-aligned box (the slab method, Kay & Kajiya 1986), for the sim
 * library's own ray integrals (sim/vdb_report.c) and the import benchmark's CPU fog.
 * (Part of the sim library; include "sim/sim.h".) The renderer has its own box entry and
 * exit for the fog volume (fog_box_entry_exit): sim does not depend on render. */
#ifndef FOGPIPE_SIM_RAY_BOX_H
#define FOGPIPE_SIM_RAY_BOX_H

/* The parameter interval [*t0, *t1] where the line origin + t dir lies in the box
 * [lo, hi] (t over the whole line: callers clamp t0 at 0 for a ray that starts at the
 * origin). Returns 1 when the interval is non-empty (t1 > t0), 0 when the line misses
 * the box; then *t0 and *t1 are unspecified. A direction component below 1e-15 in
 * magnitude counts as parallel to that slab (inside it or a miss), so nothing divides by
 * zero. */
int ray_box_clip(const double origin[3], const double dir[3], const double lo[3],
                 const double hi[3], double *t0, double *t1);

#endif
