#version 450
// Benchmark reference only (bench/vk_math_bench.cpp): the same functions as verify_math.glsl with the
// device's native GLSL operations, whose bits Vulkan leaves to the implementation. Not shared code.
layout(std430, set = 0, binding = 0) readonly buffer Inputs { float inputs[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Outputs { float outputs[]; };
layout(push_constant) uniform Push { int fn; uint count; uint width; } pc;
layout(local_size_x = 64) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec3 v = vec3(inputs[3 * i], inputs[3 * i + 1], inputs[3 * i + 2]);
  vec3 r = vec3(0.0);
#ifdef FIXED_FN
  switch (FIXED_FN) {
#else
  switch (pc.fn) {
#endif
    case 0: r.x = v.x / v.y; break;
    case 1: r.x = sqrt(v.x); break;
    case 2: r.x = inversesqrt(v.x); break;
    case 3: r = normalize(v); break;
    case 4: r.x = exp(v.x); break;
    case 5: r.x = exp2(v.x); break;
    case 6: r.x = log(v.x); break;
    case 7: r.x = log2(v.x); break;
    case 8: r.x = pow(v.x, v.y); break;
    case 9: r.x = sin(v.x); break;
    case 10: r.x = cos(v.x); break;
    case 11: r.x = atan(v.x, v.y); break;
    default: r.x = acos(v.x); break;
  }
  outputs[3 * i] = r.x;
  outputs[3 * i + 1] = r.y;
  outputs[3 * i + 2] = r.z;
}
