/* The fog-model ladder (docs/architecture.md) behind one table (render/fog_models.def): each
 * model is its parameters (fog_model), a CPU optical depth in double and a GLSL twin of
 * the same name (render/shaders/fog_models.glsl); the fog pass, the tests, the benchmarks
 * and the config reader iterate the table.
 *
 *   FOG_MODEL_FOGMAP       the 2.5D wavelet fogmap (fog_field.h), exact per knot cell
 *   FOG_MODEL_HOMOGENEOUS  K = extinction everywhere: OpenGL's GL_EXP fog, tau = e^{-K d}
 *   FOG_MODEL_HEIGHT       K = extinction exp(-(y - y0)/H): standard exponential height
 *                          fog, closed-form integral along the ray
 *   FOG_MODEL_RBF          K = extinction + sum_i c_i exp(-|x - b_i|^2 / r_i^2): Gaussian
 *                          radial basis functions over a homogeneous base (Zhou et al.,
 *                          Fogshop 2007, eq. 2 with a_i = 1/r_i), closed form with erf
 *   FOG_MODEL_VOLUME       K = a dense 3D grid, trilinear (a VDB frame as it is, where the
 *                          2.5D fogmap cannot hold it: tall plumes), exact per lattice cell
 *                          (3D DDA, two Gauss nodes) or ray-marched
 *   FOG_MODEL_QUADRIC      K = sum_i c_i min(1, -Q_i(x)/e_i) inside quadric i and its clip
 *                          box: fog in spheres, ellipsoids, cylinders, cones and general
 *                          quadrics with a soft edge, exact (piecewise quadratic along a
 *                          ray between the roots of Q_i = 0 and Q_i = -e_i)
 *   FOG_MODEL_LINEAR       OpenGL's GL_LINEAR fog (Zdrojewska eq. 2): the factor
 *                          f = (end - d)/(end - start) of the distance d from the eye,
 *                          1 before start and 0 from end on, as the view ray's
 *                          transmittance; the medium k(r) = 1/(end - r) radial about the
 *                          eye (render/fog_classic_cpu.c)
 *   FOG_MODEL_EXP2         OpenGL's GL_EXP2 fog (eq. 4): f = e^{-(a d)^2}, k(r) = 2 a^2 r
 *                          (a = extinction); GL_EXP is FOG_MODEL_HOMOGENEOUS
 *   FOG_MODEL_PERLIN       K = extinction e^{-(y - y0)/H} T(p, time) in a box: animated Perlin
 *                          turbulence (Zdrojewska 2004), octave textures drifting each with
 *                          its own wind, exact per texel cell or the paper's single sample
 *                          (render/fog_perlin.h)
 * Adding a model: see render/fog_models.def. */
#ifndef FOGPIPE_RENDER_FOG_MODELS_H
#define FOGPIPE_RENDER_FOG_MODELS_H

#include "render/fog_field.h"
#include "render/fog_perlin.h"
#include "render/volume_march.h"

#include <stdbool.h>

typedef enum fog_model_kind {
#define FOG_MODEL_ROW(KIND, id, label, keys, pyramid) FOG_MODEL_##KIND,
#include "render/fog_models.def"
#undef FOG_MODEL_ROW
  FOG_MODEL_COUNT
} fog_model_kind;

/* The most RBFs one model holds (the GL pass keeps them in a buffer texture and culls them
 * per screen tile: render/fog_rbf_tiles.h). */
#define FOG_MAX_RBFS 4096

/* One Gaussian of FOG_MODEL_RBF: extinction density exp(-|x - centre|^2 / radius^2), per
 * world unit (radius > 0: where it has fallen to 1/e). */
typedef struct fog_rbf {
  double centre[3];
  double radius;
  double density;
} fog_rbf;

/* The most quadric volumes one model holds (uniform arrays in the GL pass). */
#define FOG_MAX_QUADRICS 16

/* One fog volume of FOG_MODEL_QUADRIC. Q(x, y, z) = A x^2 + B y^2 + C z^2 + D xy + E yz +
 * F xz + G x + H y + I z + J, coefficients q[0..9] = A..J (the ten-coefficient form of the
 * ray-tracing literature), negative inside. Extinction per world unit inside the closed box
 * [lo, hi]: density * min(1, -Q/edge) where Q < 0, 0 where Q >= 0 (edge 0: a hard edge,
 * density wherever Q < 0). The shape constructors below scale Q to -1 at the core and 0 on
 * the surface, so edge is the share of that range over which the fog fades in. */
typedef struct fog_quadric {
  double q[10];
  double lo[3], hi[3];
  double density; /* >= 0 */
  double edge;    /* in [0, 1] for the shapes below; >= 0 for a general quadric */
  double noise;   /* in [0, 1]: the share of the density the turbulence modulates (below) */
} fog_quadric;
/* Doubles only: configs hash and compare it as bytes. */
_Static_assert(sizeof(fog_quadric) == 19 * sizeof(double), "fog_quadric has padding");

/* Noise inside the volumes (the course slides' noise-modulated fog volumes): a volume with
 * noise n > 0 has K = density e(Q) (1 - n + n T(p, time) / T_mean), T the Perlin
 * turbulence (render/fog_perlin.h, its octaves drifting with their winds) and T_mean its
 * mean over the texture's period, so that the fog's mean density stays `density`. A NULL
 * perlin leaves every volume homogeneous. */
typedef struct fog_quadric_noise {
  const fog_perlin *perlin;
  double time;
} fog_quadric_noise;

/* The shapes (Q normalised as above; the box is the shape's own bounds):
 * a sphere of radius r, an ellipsoid of semi-axes r[3], an upright cylinder and an upright
 * cone (apex at the top) of base radius r standing on base (its centre) with height h. */
fog_quadric fog_quadric_sphere(const double centre[3], double r, double density, double edge);
fog_quadric fog_quadric_ellipsoid(const double centre[3], const double r[3], double density,
                                  double edge);
fog_quadric fog_quadric_cylinder(const double base[3], double r, double h, double density,
                                 double edge);
fog_quadric fog_quadric_cone(const double base[3], double r, double h, double density,
                             double edge);
/* Q = x^T M x + 2 l^T x + J: the symmetric M and l from the ten coefficients. */
void fog_quadric_matrix(const fog_quadric *v, double m[3][3], double l[3]);
/* Q of one volume at p. */
double fog_quadric_value(const fog_quadric *v, const double p[3]);
/* The exact optical depth of `count` volumes from o along unit d up to length (HUGE_VAL:
 * through every box). Per volume: the ray's stretch in the box; the roots of Q(t) = 0 and
 * Q(t) = -edge on it (Q(o + t d) = a t^2 + 2 b t + c, roots without cancellation: q = -(b +
 * sign(b) sqrt(b^2 - a c)), t = q/a and c/q; a tangent ray has a double root, a = 0 one);
 * between consecutive breaks K is 0, density, or density (-Q/edge), a quadratic integrated
 * exactly by Simpson's rule. With noise, the turbulence's share is cut further at every
 * octave's texel cells, where it is trilinear (a cubic along the ray): times the quadratic
 * weight a quintic, which 3 Gauss-Legendre nodes integrate exactly. */
double fog_quadric_optical_depth(const fog_quadric *v, int count, const fog_quadric_noise *noise,
                                 const double o[3], const double d[3], double length);
/* Where a ray o + t d crosses a volume's surfaces inside (t0, t1): Q = 0, Q = -edge, and
 * the faces of its clip box where Q < 0 there (K jumps or kinks at each, and is smooth
 * between): at most FOG_QUADRIC_MAX_CUTS, unsorted; returns how many. The sun's mean cuts
 * its segments there (fog_sun_mean_light). */
#define FOG_QUADRIC_MAX_CUTS (6 * FOG_MAX_QUADRICS)
int fog_quadric_cuts(const fog_quadric *v, int count, const double o[3], const double d[3],
                     double t0, double t1, double cuts[FOG_QUADRIC_MAX_CUTS]);
/* K at p: the sum of the volumes' extinctions. */
double fog_quadric_extinction_at(const fog_quadric *v, int count, const fog_quadric_noise *noise,
                                 const double p[3]);
/* Whether any of the volumes has noise > 0. */
bool fog_quadric_noisy(const fog_quadric *v, int count);
/* The union of the volumes' boxes (false for count < 1). */
bool fog_quadric_bounds(const fog_quadric *v, int count, double lo[3], double hi[3]);

/* Below |a| L < FOG_EXPREL_SWITCH the height fog's (1 - e^{-aL})/(aL) is a series
 * (it cancels in float otherwise; tests/render/test_integral_models.c). */
#define FOG_EXPREL_SWITCH 0.1

typedef struct fog_model {
  fog_model_kind kind;
  /* FOG_MODEL_FOGMAP: the placement, the pyramid (levels = 0 for one grid) and the method. */
  const fog_volume *volume;
  const fog_lod *lod;
  fog_lod_method lod_method;
  /* FOG_MODEL_HOMOGENEOUS and FOG_MODEL_HEIGHT: extinction per world unit (at y0 for the
   * height fog), y0 and the scale height H > 0. FOG_MODEL_RBF: extinction is the base. */
  double extinction, y0, scale_height;
  /* FOG_MODEL_RBF: rbf_count (<= FOG_MAX_RBFS) Gaussians, world coordinates. */
  const fog_rbf *rbfs;
  int rbf_count;
  /* FOG_MODEL_VOLUME: the grid (extinction per world unit; render/volume_march.h's
   * placement). fog_model_optical_depth integrates it exactly. */
  const volume_grid_desc *grid3d;
  /* FOG_MODEL_QUADRIC: quadric_count (<= FOG_MAX_QUADRICS) volumes, world coordinates. Any
   * other kind: quadric volumes beside the model's fog (fog_model_quadrics_beside), their
   * extinction added to the model's wherever K is read, their optical depth exact. */
  const fog_quadric *quadrics;
  int quadric_count;
  /* FOG_MODEL_LINEAR and FOG_MODEL_EXP2 (the classic factors): the eye their distances count
   * from (the camera that draws them), and the linear fog's 0 <= start < end. */
  double eye[3];
  double fog_start, fog_end;
  /* FOG_MODEL_PERLIN: the octaves (extinction, y0 and scale_height are the height fog's),
   * the animation time in seconds and the integral. Quadric volumes with noise: the
   * octaves and the time of their turbulence. */
  const fog_perlin *perlin;
  double time;
  fog_perlin_integral perlin_integral;
} fog_model;

/* Whether quadric volumes stand beside the model's own fog (a kind other than
 * FOG_MODEL_QUADRIC with quadric_count > 0). */
bool fog_model_quadrics_beside(const fog_model *model);
/* The model without the quadrics beside it (itself otherwise). */
fog_model fog_model_alone(const fog_model *model);

/* The turbulence of the model's quadric volumes: its perlin and time (the Perlin model's
 * own octaves, or those of `quadric` volumes with noise). */
fog_quadric_noise fog_model_quadric_noise(const fog_model *model);

/* FOG_MODEL_PERLIN's medium of a model. */
fog_perlin_medium fog_model_perlin_medium(const fog_model *model);

/* Optical depth from the camera along the unit direction dir up to the first surface
 * t_surface (HUGE_VAL: none; homogeneous and downward height fog then give +inf): the
 * model's CPU twin from the table, plus the quadrics beside it. */
double fog_model_optical_depth(const fog_model *model, const double camera[3],
                               const double dir[3], double t_surface);

/* A CPU twin: fog_model_depth_<id> of the table's row. */
typedef double (*fog_model_depth_fn)(const fog_model *model, const double camera[3],
                                     const double dir[3], double t_surface);

/* One row of render/fog_models.def. */
typedef struct fog_model_info {
  fog_model_kind kind;
  const char *name;  /* `[fog] model = name`; the GLSL twins are fog_model_depth_<name> and
                        fog_model_march_<name> */
  const char *label; /* in charts and benchmark tables */
  const char *keys;  /* the [fog] keys it reads besides colour, space-separated */
  bool pyramid;      /* has a wavelet pyramid (transformed per frame) */
  fog_model_depth_fn optical_depth;
} fog_model_info;

/* The table, indexed by kind (FOG_MODEL_COUNT rows). */
extern const fog_model_info fog_model_table[FOG_MODEL_COUNT];
/* The row of a config name, or NULL. */
const fog_model_info *fog_model_find(const char *name);

/* The twins the table names, one per row. */
#define FOG_MODEL_ROW(KIND, id, label, keys, pyramid)                                    \
  double fog_model_depth_##id(const fog_model *model, const double camera[3],            \
                              const double dir[3], double t_surface);
#include "render/fog_models.def"
#undef FOG_MODEL_ROW

double fog_homogeneous_optical_depth(double extinction, double length);
/* The classic factors' media (render/fog_classic_cpu.c): k at distance r from the eye, and
 * the exact optical depth from o along unit d up to length, for any o (from the eye:
 * ln((end - start)/(end - L)) past start, +inf from end on; (a L)^2). */
double fog_linear_extinction(double start, double end, double r);
/* Whether the model's medium is radial about model->eye (the classic factors): its users set
 * the eye to the camera that looks. */
bool fog_model_about_eye(const fog_model *model);
double fog_exp2_extinction(double density, double r);
double fog_linear_optical_depth(double start, double end, const double eye[3],
                                const double o[3], const double d[3], double length);
double fog_exp2_optical_depth(double density, const double eye[3], const double o[3],
                              const double d[3], double length);
/* int_0^L k exp(-(y_c + t dir_y - y0)/H) dt = k e^{-(y_c - y0)/H} L exprel(dir_y L / H). */
double fog_height_optical_depth(double extinction, double y0, double scale_height,
                                double camera_y, double dir_y, double length);
/* (1 - e^{-x})/x, with the series below FOG_EXPREL_SWITCH (the GLSL twin's form). */
double fog_exprel(double x);
/* base L + sum_i int_0^L c_i exp(-|o + t d - b_i|^2 / r_i^2) dt for the unit direction d
 * from o: each Gaussian is e^{-h^2/r^2} r sqrt(pi)/2 (erf(u1) - erf(u0)), h its distance
 * from the ray's line, u0 = -t_c/r, u1 = (L - t_c)/r, t_c the ray parameter nearest it.
 * length HUGE_VAL: to infinity (+inf if base > 0). */
double fog_rbf_optical_depth(double base, const fog_rbf *rbfs, int count, const double camera[3],
                             const double dir[3], double length);
/* The volume's optical depth up to length, over the ray's stretch inside the grid's
 * support (index coordinates in [-1, dim]: trilinear with zero beyond the outer voxels)
 * from t >= 0. Exact: trilinear is a cubic in t inside each cell of the integer lattice of
 * index space, so a 3D DDA over those cells with two Gauss-Legendre nodes per piece. The
 * march: n = ceil(stretch / step) equal steps, midpoint samples. Both in double; the GLSL
 * twins take the same samples with the hardware's trilinear filter. */
double fog_grid3d_optical_depth(const volume_grid_desc *grid, const double camera[3],
                                const double dir[3], double length);
double fog_grid3d_optical_depth_march(const volume_grid_desc *grid, double step,
                                      const double camera[3], const double dir[3],
                                      double length);
/* The light a view ray gathers through the volume per lattice cell of its exact walk, as
 * fog_perlin_light_integral does for Perlin fog: S = int_0^L tau K f du, `nodes` (1..4)
 * Gauss-Legendre nodes a cell piece, tau at a node from the running depth plus the partial
 * integral of the polynomial through the piece's nodes; *depth the walk's optical depth. */
double fog_grid3d_light_integral(const volume_grid_desc *grid, const double camera[3],
                                 const double dir[3], double length, int nodes,
                                 double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth);
/* The same for the 2.5D fogmap, per piece of its exact walk (fog_optical_depth's pieces:
 * the knot cells of `grid` crossed, and the profile's breaks: a B-spline's knots, or the
 * exponential's y0 + k H/2 as the GLSL walk cuts it). K at a node is the grid's f times g
 * times the volume's extinction; the ray is clipped to the box and to [0, length]. */
double fog_fogmap_light_integral(const fog_volume *volume, const transform_grid *grid,
                                 const double camera[3], const double dir[3], double length,
                                 int nodes, double depth_limit, fog_point_light_fn light,
                                 const void *user, double *depth);
/* The volume's trilinear K at world point p (zero beyond the outer voxels). */
double fog_grid3d_extinction_at(const volume_grid_desc *grid, const double p[3]);
/* erf(u1) - erf(u0) for u0 <= u1 without cancellation: through erfc where both have the
 * same sign (erf(7) - erf(6) is 2.2e-17, not 0). */
double fog_erf_difference(double u0, double u1);

#endif
