/* The volume model (render/volume_march.h's grid, trilinear between voxel centres, zero
 * beyond the outer voxels) as a medium of the light reference (fog_light_reference.h): its
 * density evaluated here from the voxels, its breaks every crossing of an integer plane of
 * index space (listed, not walked). For a grid whose index_from_world is diagonal (each
 * index axis a scaled world axis), the support's world box exact. g must outlive the
 * medium. */
#ifndef FOGPIPE_TESTS_REFERENCE_VOLUME_REFERENCE_H
#define FOGPIPE_TESTS_REFERENCE_VOLUME_REFERENCE_H

#include "reference/fog_light_reference.h"
#include "render/volume_march.h"

light_ref_medium light_ref_volume_medium(const volume_grid_desc *g);

#endif
