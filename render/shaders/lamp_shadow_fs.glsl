#version 430 core
// A lamp's shadow cube: the distance from the lamp over its far, linear (lamp_shadow.glsl
// compares distances).
in vec3 v_from_lamp;
uniform float inv_far;

void main() { gl_FragDepth = length(v_from_lamp) * inv_far; }
