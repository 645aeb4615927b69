/* Sunlight in the fog: single scattering (docs/light.md).
 *
 *   L(O) = tau(O,P) L(P) + int_0^d tau(O,u) K(u) [L_amb + a L_sun p(theta) T_s(u) V(u)] du
 *
 * L_amb is the fog colour (isotropic ambient in-scatter), a the scattering albedo
 * (sigma_s = a K), p the Henyey-Greenstein phase function with cos theta = w_sun . w_view.
 * For a sun theta is constant along a view ray, so with T_s = V = 1 the integral is, for
 * any density, exactly (L_amb + a L_sun p(theta)) (1 - tau): int_0^d tau K du = 1 - tau
 * (fog_inscatter_unshadowed below). The renderer draws the shadows too: T_s, the fog's on
 * itself (render/fog_sun_shadow.h), and V, the terrain's and boxes' (light shafts:
 * render/sun_shadow_map.h), through their tau K-weighted mean M along the ray:
 * (L_amb + a L_sun p(theta) M) (1 - tau) (fog_sun_mean_light, fog_light.glsl); a = 0 is
 * Giroud & Biri's eq. 4 bit for bit. */
#ifndef FOGPIPE_RENDER_FOG_LIGHT_H
#define FOGPIPE_RENDER_FOG_LIGHT_H

/* The sun as the fog sees it. Every field is a value (zero is zero). */
typedef struct fog_sun {
  double albedo;       /* a in [0, 1]; 0: no sunlight in the fog */
  double phase_g;      /* Henyey-Greenstein g in (-1, 1): > 0 forward, 0 isotropic */
  double direction[3]; /* unit vector towards the sun */
  double radiance[3];  /* L_sun, linear: the sun's irradiance (pi x the [light] sun_colour
                          that lights the surfaces, whose Lambert term has no 1/pi) */
} fog_sun;

/* |g| stays below this: p(0) = (1 + g) / (4 pi (1 - g)^2) is 1.6e5 at g = 0.999. */
#define FOG_PHASE_G_MAX 0.999

/* p(theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^{3/2}), per steradian: integrates
 * to 1 over the sphere (Henyey & Greenstein 1941). */
double fog_phase_hg(double g, double cos_theta);

/* The sun's apparent radius, radians (0.27 degrees). */
#define FOG_SUN_ANGULAR_RADIUS 0.0047

/* The share of the sun's disc above the horizon, for the unit direction towards it: 1 from
 * an elevation of +FOG_SUN_ANGULAR_RADIUS, 0 below minus it, linear in the sine between
 * (0.5 with the sun's centre on the horizon). At the scene's scale the ground plane is the
 * horizon: a sun below it lights neither the fog nor the surfaces (the demo's dusk), which
 * the fog pass, its CPU twin, the surfaces and the sky all take from here. */
double fog_sun_above_horizon(const double direction[3]);

/* The in-scattered radiance of a view ray (unit view_dir, from the camera) of transmittance
 * tau, without shadows: (ambient + a L_sun p(theta)) (1 - tau), per channel; L_sun times
 * fog_sun_above_horizon. */
void fog_inscatter_unshadowed(double tau, const double ambient[3], const fog_sun *sun,
                              const double view_dir[3], double out[3]);

#endif
