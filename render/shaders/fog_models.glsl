// The analytic fog models: GLSL twins of render/fog_models_cpu.c (same names, same
// formulas; render/fog_models.h). Heights arrive camera-relative from the CPU.
#define FOG_MODEL_FOGMAP 0
#define FOG_MODEL_HOMOGENEOUS 1
#define FOG_MODEL_HEIGHT 2
#define FOG_EXPREL_SWITCH 0.1

#ifdef FOG_MODEL_KIND
const int fog_model = FOG_MODEL_KIND;  // specialised per variant (render/fog_pass.c)
#else
uniform int fog_model;
#endif
uniform float fog_model_extinction;
uniform float fog_model_y0;            // y0 - camera y
uniform float fog_model_scale_height;

// (1 - e^{-x})/x, with the series sum_{n<=10} (-x)^n/(n+1)! below FOG_EXPREL_SWITCH.
float fog_exprel(float x) {
  if (abs(x) < FOG_EXPREL_SWITCH)
    return 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 6.0 + x * (-1.0 / 24.0 + x * (1.0 / 120.0 +
           x * (-1.0 / 720.0 + x * (1.0 / 5040.0 + x * (-1.0 / 40320.0 +
           x * (1.0 / 362880.0 + x * (-1.0 / 3628800.0 + x * (1.0 / 39916800.0))))))))));
  return (1.0 - exp(-x)) / x;
}

float fog_homogeneous_optical_depth(float extinction, float length) {
  return extinction * length;  // OpenGL GL_EXP fog
}

// int_0^L k exp(-(y_c + t dir_y - y0)/H) dt = k e^{-(y_c - y0)/H} L exprel(dir_y L / H);
// camera-relative: y_c = 0, y0 = fog_model_y0. length >= 1e29 means no surface.
float fog_height_optical_depth(float extinction, float y0, float scale_height, float dir_y,
                               float length) {
  float k = extinction * exp(y0 / scale_height);
  float a = dir_y / scale_height;
  if (length >= 1e29) return a > 0.0 ? k / a : 1e30;
  return k * length * fog_exprel(a * length);
}
