#version 430 core
// The fog pass's full-screen triangle from gl_VertexID (a VAO must be bound in core profile).
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
