#version 430 core
// Scene pass (render/scene.c): terrain and boxes, camera-relative (render/camera.h).
layout(location = 0) in vec3 position;  // relative to the terrain origin
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;

uniform vec3 offset;         // terrain origin - camera position, computed in double
uniform mat4 view_rotation;  // camera_view_matrix: rotation only
uniform mat4 projection;   // far at infinity (camera_projection_matrix_infinite)
uniform float far_plane;   // the cut at far: gl_ClipDistance[0] (the camera pass enables it)

out vec3 v_relative;  // surface point - camera
out vec3 v_normal;
out vec3 v_albedo;

void main() {
  vec3 relative = position + offset;
  v_relative = relative;
  v_normal = normal;
  v_albedo = albedo;
  vec4 eye = view_rotation * vec4(relative, 1.0);
  gl_ClipDistance[0] = far_plane + eye.z;  // eye z is minus the depth along the view axis
  gl_Position = projection * eye;
}
