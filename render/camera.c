/* The pinhole camera (see camera.h for the conventions and the GLSL twin). */
#include "render/camera.h"

#include <math.h>

static double camera_aspect(const camera *cam, int width, int height) {
  if (cam->aspect != CAMERA_ASPECT_OF_IMAGE) return cam->aspect;
  return height > 0 ? (double)width / (double)height : 1.0;
}

/* forward, right, up as unit vectors (right-handed: right x up = -forward). */
static void camera_axes(const camera *cam, double right[3], double up[3], double forward[3]) {
  double cy = cos(cam->yaw), sy = sin(cam->yaw), cp = cos(cam->pitch), sp = sin(cam->pitch);
  forward[0] = cp * sy;
  forward[1] = sp;
  forward[2] = -cp * cy;
  right[0] = cy;
  right[1] = 0.0;
  right[2] = sy;
  /* up = right x forward */
  up[0] = right[1] * forward[2] - right[2] * forward[1];
  up[1] = right[2] * forward[0] - right[0] * forward[2];
  up[2] = right[0] * forward[1] - right[1] * forward[0];
}

bool camera_equal(const camera *a, const camera *b) {
  return a->position[0] == b->position[0] && a->position[1] == b->position[1] &&
         a->position[2] == b->position[2] && a->yaw == b->yaw && a->pitch == b->pitch &&
         a->fov_y == b->fov_y && a->aspect == b->aspect && a->near_plane == b->near_plane &&
         a->far_plane == b->far_plane;
}

void camera_look_at(camera *cam, const double target[3]) {
  double d[3] = {target[0] - cam->position[0], target[1] - cam->position[1],
                 target[2] - cam->position[2]};
  double horizontal = sqrt(d[0] * d[0] + d[2] * d[2]);
  /* straight up or down: yaw 0, as a pitch of +-90 draws (atan2(0, -0) is pi: the image
   * turned half round, the window then showing another view than `render`) */
  cam->yaw = horizontal > 0.0 ? atan2(d[0], -d[2]) : 0.0;
  cam->pitch = atan2(d[1], horizontal);
}

void camera_basis(const camera *cam, int width, int height, double right[3], double up[3],
                  double forward[3]) {
  double half_h = tan(0.5 * cam->fov_y);
  double half_w = half_h * camera_aspect(cam, width, height);
  camera_axes(cam, right, up, forward);
  for (int i = 0; i < 3; i++) {
    right[i] *= half_w;
    up[i] *= half_h;
  }
}

void camera_ray(const camera *cam, double px, double py, int width, int height,
                double origin[3], double dir[3]) {
  double right[3], up[3], forward[3];
  camera_basis(cam, width, height, right, up, forward);
  /* Same arithmetic as the shader: ndc from the GL fragment centre, y up. */
  double ndc_x = 2.0 * (px + 0.5) / width - 1.0;
  double ndc_y = 1.0 - 2.0 * (py + 0.5) / height;
  double len2 = 0.0;
  for (int i = 0; i < 3; i++) {
    origin[i] = cam->position[i];
    dir[i] = forward[i] + ndc_x * right[i] + ndc_y * up[i];
    len2 += dir[i] * dir[i];
  }
  double inv = 1.0 / sqrt(len2);
  for (int i = 0; i < 3; i++) dir[i] *= inv;
}

void camera_view_matrix(const camera *cam, float m[16]) {
  double r[3], u[3], f[3];
  camera_axes(cam, r, u, f);
  /* Rows of the rotation are right, up, -forward (OpenGL eye space looks down -Z). */
  for (int c = 0; c < 3; c++) {
    m[c * 4 + 0] = (float)r[c];
    m[c * 4 + 1] = (float)u[c];
    m[c * 4 + 2] = (float)-f[c];
    m[c * 4 + 3] = 0.0f;
  }
  m[12] = m[13] = m[14] = 0.0f;
  m[15] = 1.0f;
}

void camera_view_matrix_world(const camera *cam, float m[16]) {
  double r[3], u[3], f[3];
  camera_axes(cam, r, u, f);
  camera_view_matrix(cam, m);
  const double *p = cam->position;
  m[12] = (float)-(r[0] * p[0] + r[1] * p[1] + r[2] * p[2]);
  m[13] = (float)-(u[0] * p[0] + u[1] * p[1] + u[2] * p[2]);
  m[14] = (float)(f[0] * p[0] + f[1] * p[1] + f[2] * p[2]);
}

void camera_projection_matrix_infinite(const camera *cam, int width, int height, float m[16]) {
  camera_projection_matrix(cam, width, height, m);
  /* far -> infinity: clip z = -z_e - 2n, window depth 1 - n/d, below 1 (the sky's depth)
   * for every d a config allows (d < 1e7 n: 1 - 1e-7 is a float below 1) */
  m[10] = -1.0f;
  m[14] = (float)(-2.0 * cam->near_plane);
}

void camera_exr_matrices(const camera *cam, int width, int height, float world_to_camera[16],
                         float world_to_ndc[16]) {
  float view[16], projection[16];
  camera_view_matrix_world(cam, view);
  camera_projection_matrix(cam, width, height, projection);
  /* column-major: (P V)[col c][row r] = sum_k P[k][r] V[c][k], GL's clip space; then
   * OpenEXR's NDC from it: x' = (x + w) / 2, y' = (w - y) / 2 (y down, the display window's
   * upper left corner at (0, 0), its lower right at (1, 1)), z and w kept */
  for (int c = 0; c < 4; c++) {
    double clip[4];
    for (int r = 0; r < 4; r++) {
      clip[r] = 0.0;
      for (int k = 0; k < 4; k++) clip[r] += (double)projection[4 * k + r] * view[4 * c + k];
    }
    world_to_ndc[4 * c + 0] = (float)(0.5 * (clip[0] + clip[3]));
    world_to_ndc[4 * c + 1] = (float)(0.5 * (clip[3] - clip[1]));
    world_to_ndc[4 * c + 2] = (float)clip[2];
    world_to_ndc[4 * c + 3] = (float)clip[3];
    /* OpenEXR's camera space is RenderMan's: left-handed, looking down +Z (GL's z negated) */
    for (int r = 0; r < 4; r++)
      world_to_camera[4 * c + r] = r == 2 ? -view[4 * c + r] : view[4 * c + r];
  }
}

void camera_depth_range(const camera *cam, double *near_plane, double *far_plane) {
  *near_plane = cam->near_plane;
  *far_plane = cam->far_plane;
}

void camera_projection_matrix(const camera *cam, int width, int height, float m[16]) {
  double n, fa;
  camera_depth_range(cam, &n, &fa);
  double t = 1.0 / tan(0.5 * cam->fov_y);
  double a = camera_aspect(cam, width, height);
  for (int i = 0; i < 16; i++) m[i] = 0.0f;
  m[0] = (float)(t / a);
  m[5] = (float)t;
  m[10] = (float)(-(fa + n) / (fa - n));
  m[11] = -1.0f;
  m[14] = (float)(-2.0 * fa * n / (fa - n));
}
