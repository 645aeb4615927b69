/* A pinhole camera: the one definition of "the ray through a pixel" shared by the CPU
 * reference, the GL passes and the tests.
 *
 * World: Y up; the fog's map spans X and Z. yaw = pitch = 0 looks along -Z with +X to
 * the right; positive yaw turns toward +X, positive pitch looks up.
 *
 * Pixels: (px, py) with row 0 at the TOP of the image; the ray goes through the pixel
 * centre (px + 0.5, py + 0.5). GL's gl_FragCoord and glReadPixels count rows from the
 * BOTTOM: GL row y_gl is image row py = height - 1 - y_gl. camera_ray() already maps to
 * the same ray a fragment at gl_FragCoord = (px + 0.5, height - py - 0.5) computes.
 *
 * How the GLSL makes exactly the same rays: camera_basis() gives three vectors, in double;
 * the shader gets them as uniforms (float) and computes, as camera_ray() does,
 *     ndc = 2 * gl_FragCoord.xy / vec2(width, height) - 1        (y up)
 *     dir = normalize(forward + ndc.x * right + ndc.y * up)
 * (right and up already scaled by tan(fov/2)*aspect and tan(fov/2)). The ray origin is
 * the camera itself: all fog passes work in camera-relative coordinates (the fog's
 * position minus the camera position, computed in double on the CPU), so a 50 km ray
 * keeps its precision in float. */
#ifndef FOGPIPE_RENDER_CAMERA_H
#define FOGPIPE_RENDER_CAMERA_H

#include <stdbool.h>

typedef struct camera {
  double position[3];            /* world */
  double yaw, pitch;             /* radians (see above) */
  double fov_y;                  /* vertical field of view, radians, in (0, pi) */
  double aspect;                 /* width / height, or CAMERA_ASPECT_OF_IMAGE */
  double near_plane, far_plane;  /* projection only: 0 < near < far */
} camera;

/* A camera's values are taken as given (no "0 means default" for a physical quantity);
 * these are what a caller without an opinion writes. */
#define CAMERA_DEFAULT_FOV_Y 1.0471975511965976 /* 60 degrees */
#define CAMERA_DEFAULT_NEAR 0.1
#define CAMERA_DEFAULT_FAR 100000.0
/* aspect: the image's width / height, whatever its size (a mode, not a ratio). */
#define CAMERA_ASPECT_OF_IMAGE 0.0

/* Whether two cameras see the same image (every field equal): a rendered view may be
 * reused while the camera has not moved. */
bool camera_equal(const camera *a, const camera *b);

/* Points the camera at a world position (sets yaw and pitch). */
void camera_look_at(camera *cam, const double target[3]);

/* The shader's ray basis for a width x height image (see above): forward is a unit
 * vector, right and up are scaled by the half-extent of the image plane at distance 1. */
void camera_basis(const camera *cam, int width, int height, double right[3], double up[3],
                  double forward[3]);

/* The unit-length ray through the centre of pixel (px, py) (row 0 at the top): origin is
 * the camera position, dir the direction. px, py may be fractional (sub-pixel jitter). */
void camera_ray(const camera *cam, double px, double py, int width, int height,
                double origin[3], double dir[3]);

/* GL matrices (column-major float[16]) for rasterised passes. The view matrix is
 * camera-relative (rotation only): draw vertices as (world - cam->position), computed in
 * double, so large worlds keep float precision. camera_view_matrix_world includes the
 * translation, for small scenes. The projection is OpenGL's perspective (clip z in
 * [-w, w]) with the camera's near and far planes. */
void camera_view_matrix(const camera *cam, float m[16]);
void camera_view_matrix_world(const camera *cam, float m[16]);
void camera_projection_matrix(const camera *cam, int width, int height, float m[16]);
/* The same with the far plane at infinity (the scene pass, which cuts at far with a clip
 * distance): the finite far put window depths within float rounding of 1, the sky's, over
 * the last 2.5 % of far at near/far 1e-6 and 45 % at 1e-7 (llvmpipe), and the sky took
 * those surfaces. */
void camera_projection_matrix_infinite(const camera *cam, int width, int height, float m[16]);
/* The standard EXR header matrices of a frame as OpenEXR defines them (ImfStandardAttributes:
 * M44f for row vectors, p' = p M, row-major: the same 16 floats as GL's column-major
 * matrices for column vectors): worldToCamera to RenderMan's camera space (left-handed: x
 * right, y up, looking down +Z, points in front at z > 0), and worldToNDC to its NDC
 * (divide by w: x right, y down, (0, 0) the image's upper left corner, (1, 1) its lower
 * right; z is GL's clip z, which readers discard). */
void camera_exr_matrices(const camera *cam, int width, int height, float world_to_camera[16],
                         float world_to_ndc[16]);
/* The near and far plane distances the projection uses (the camera's own: set both). */
void camera_depth_range(const camera *cam, double *near_plane, double *far_plane);

#endif
