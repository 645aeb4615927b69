#version 430 core
// Shows a linear colour texture in a window (render/gl_present.h): scaled to the viewport,
// nearest texel or the texture's bilinear filter, the display transform (render/display.h:
// exposure, tone map), the sRGB transfer function (IEC 61966-2-1) and the 8-bit ordered
// dither, as `fogpipe render` applies for PNG output.
uniform sampler2D image;
uniform vec2 image_per_pixel;  // image size / viewport size
uniform int bilinear;          // 1: texture() at the pixel's centre; 0: its texel
uniform float exposure_scale;  // 2^exposure
uniform int tone_map;          // display_tone_map: 0 clamp, 1 ACES fit, 2 Reinhard
uniform int dither;            // 1: ordered dithering to 8 bits, 0: the framebuffer rounds
uniform int top_row;           // viewport height - 1: row y from the top is top_row - fragment y

// display_map in render/display.c
vec3 display_map(vec3 linear) {
  // NaN and negative to 0, as in C (max() leaves NaN undefined)
  vec3 x = mix(max(linear * exposure_scale, vec3(0.0)), vec3(0.0), isnan(linear));
  if (tone_map == 1)  // Narkowicz's fit of the ACES filmic curve (2015)
    x = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
  else if (tone_map == 2)  // Reinhard et al. 2002, eq. 3
    x = x / (1.0 + x);
  return min(x, vec3(1.0));
}

layout(location = 0) out vec4 colour;

vec3 srgb_encode(vec3 linear) {
  linear = clamp(linear, 0.0, 1.0);
  return mix(12.92 * linear, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055,
             step(vec3(0.0031308), linear));
}

// srgb8_dither_level in sim/image_srgb.c: the 8 x 8 Bayer matrix's level at p (row 0 at the top)
int dither_level(ivec2 p) {
  int level = 0;
  for (int bit = 0; bit < 3; bit++)
    level = (level << 2) | ((((p.x ^ p.y) >> bit) & 1) << 1) | ((p.y >> bit) & 1);
  return level;
}

void main() {
  ivec2 size = textureSize(image, 0);
  vec3 c;
  if (bilinear != 0) {
    c = texture(image, gl_FragCoord.xy * image_per_pixel / vec2(size)).rgb;
  } else {
    ivec2 p = min(ivec2(gl_FragCoord.xy * image_per_pixel), size - 1);
    c = texelFetch(image, p, 0).rgb;
  }
  vec3 s = srgb_encode(display_map(c));
  if (dither != 0) {  // srgb8_encode_dithered: floor(255 s + (b + 1/2)/64), an exact 8-bit level
    ivec2 p = ivec2(int(gl_FragCoord.x), top_row - int(gl_FragCoord.y));
    s = min(floor(255.0 * s + (float(dither_level(p)) + 0.5) / 64.0), 255.0) / 255.0;
  }
  colour = vec4(s, 1.0);
}
