#version 430 core
// Shows a linear colour texture in a window: nearest-pixel scaling to the viewport and the
// sRGB transfer function (IEC 61966-2-1), as `fogpipe render` applies for PNG output.
uniform sampler2D image;
uniform vec2 image_per_pixel;  // image size / viewport size

layout(location = 0) out vec4 colour;

vec3 srgb_encode(vec3 linear) {
  linear = clamp(linear, 0.0, 1.0);
  return mix(12.92 * linear, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055,
             step(vec3(0.0031308), linear));
}

void main() {
  ivec2 size = textureSize(image, 0);
  ivec2 p = min(ivec2(gl_FragCoord.xy * image_per_pixel), size - 1);
  colour = vec4(srgb_encode(texelFetch(image, p, 0).rgb), 1.0);
}
