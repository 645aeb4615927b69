/* View-frustum planes from camera_basis (render/camera.h) and a box test. */
#include "render/frustum.h"

#include "render/vec3.h"

/* Relative slack: the side planes pass through the image corners scaled by 1 + SLACK, the
 * far plane moves out by SLACK of its distance. It covers float rounding of the GL
 * vertices and matrices (~1e-7 relative), many times over. */
#define SLACK 1e-3

void frustum_from_camera(frustum *f, const camera *cam, int width, int height) {
  double right[3], up[3], forward[3];
  camera_basis(cam, width, height, right, up, forward);
  /* corner[sx][sy]: the ray direction through image corner (2 sx - 1, 2 sy - 1) */
  double corner[2][2][3];
  for (int sx = 0; sx < 2; sx++)
    for (int sy = 0; sy < 2; sy++)
      for (int i = 0; i < 3; i++)
        corner[sx][sy][i] = forward[i] + (1.0 + SLACK) * ((2 * sx - 1) * right[i] +
                                                         (2 * sy - 1) * up[i]);
  /* side planes through the camera, each spanned by the two corner rays of one edge */
  const double *edges[4][2] = {{corner[0][0], corner[0][1]}, {corner[1][0], corner[1][1]},
                               {corner[0][0], corner[1][0]}, {corner[0][1], corner[1][1]}};
  for (int k = 0; k < 4; k++) {
    vec3_cross(edges[k][0], edges[k][1], f->normal[k]);
    if (vec3_dot(f->normal[k], forward) < 0)
      for (int i = 0; i < 3; i++) f->normal[k][i] = -f->normal[k][i];
    f->offset[k] = 0.0;
  }
  double near, far;
  camera_depth_range(cam, &near, &far);
  for (int i = 0; i < 3; i++) f->normal[4][i] = forward[i], f->normal[5][i] = -forward[i];
  /* At half the near distance: far from rounding, and still culling every box wholly
   * behind the camera, which the side planes alone may not (test_frustum). */
  f->offset[4] = -0.5 * near;
  f->offset[5] = (1.0 + SLACK) * far;
}

bool frustum_culls_box(const frustum *f, const double lo[3], const double hi[3]) {
  for (int k = 0; k < 6; k++) {
    /* the box's corner farthest along the plane's normal */
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = f->normal[k][i] >= 0 ? hi[i] : lo[i];
    if (vec3_dot(f->normal[k], p) + f->offset[k] < 0) return true;
  }
  return false;
}
