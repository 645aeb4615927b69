#version 430 core
// The loop-cap probe (render/gl_loop_cap.c): one loop of loop_cap_iterations, its count
// out. A renderer that ends loops early (Mesa's llvmpipe: 65535 iterations of all a
// shader's loops together) writes fewer.
uniform int loop_cap_iterations;
out float loop_cap_count;
void main() {
  float count = 0.0;  // exact to 2^24
  for (int i = 0; i < loop_cap_iterations; i++) count += 1.0;
  loop_cap_count = count;
}
