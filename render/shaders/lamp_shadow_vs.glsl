#version 430 core
// A lamp's shadow cube (render/scene_lamp_shadow.c): the terrain and boxes seen from the
// lamp, one face at a time.
layout(location = 0) in vec3 position;  // relative to the terrain origin

uniform vec3 offset;    // terrain origin - lamp, computed in double
uniform mat4 face_clip; // lamp_shadow_face_clip: from the lamp to the face's clip space

out vec3 v_from_lamp;

void main() {
  v_from_lamp = position + offset;
  gl_Position = face_clip * vec4(v_from_lamp, 1.0);
}
