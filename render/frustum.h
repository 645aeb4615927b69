/* The camera's view volume as planes, to skip geometry it cannot see (scene.c culls the
 * terrain's tiles with it). Camera-relative coordinates (world - camera position), double.
 * Conservative: a box is culled only when it lies wholly outside one plane, and the planes
 * sit a little outside the true frustum, so culling never removes a visible pixel. */
#ifndef FOGPIPE_RENDER_FRUSTUM_H
#define FOGPIPE_RENDER_FRUSTUM_H

#include <stdbool.h>

#include "render/camera.h"

typedef struct frustum {
  /* inside plane k: normal[k] . p + offset[k] >= 0; left, right, bottom, top, near, far */
  double normal[6][3], offset[6];
} frustum;

/* The volume the projection of camera_projection_matrix keeps, for a width x height image. */
void frustum_from_camera(frustum *f, const camera *cam, int width, int height);

/* True when no point of the axis-aligned box [lo, hi] (camera-relative) can be seen. */
bool frustum_culls_box(const frustum *f, const double lo[3], const double hi[3]);

#endif
