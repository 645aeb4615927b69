/* Two frames of a played VDB volume sequence blended for a time between them
 * (app/render_fog.c): (1 - w)·a + w·b voxel by voxel, where the two frames share their
 * voxels' placement. */
#ifndef FOGPIPE_APP_VOLUME_BLEND_H
#define FOGPIPE_APP_VOLUME_BLEND_H

#include <stdbool.h>

#include "render/volume_march.h"
#include "sim/vdb_import.h"

/* Frames a and b share their voxels' placement (the same VDB transform and up axis), so
 * their grids can be laid over each other index by index. */
bool volume_blend_placed_alike(const vdb_frame *a, const vdb_frame *b);

/* (1 - w) a + w b on the union of the index boxes of the frames that hold fog (zero beyond
 * each), into out (its values malloc'd: the caller frees them); the placement is a's with
 * the union's corner. A frame without fog (active_voxels 0: the one voxel of 0 at index
 * (0, 0, 0) that stands for a sequence's empty frame) adds nothing and takes no room. */
int volume_blend(const vdb_frame *fa, const volume_grid_desc *a, const vdb_frame *fb,
                 const volume_grid_desc *b, double w, volume_grid_desc *out, fog_error *err);

#endif
