#version 450
// Entry point of `shadetwin verify texture`: one textureLod (mode 0) or texelFetch (mode 1) per
// invocation; query = (u, v, layer, lod), or the int bits of (x, y, layer, level) for texelFetch.
layout(set = 0, binding = 0) uniform sampler2DArray tex;
layout(std430, set = 0, binding = 1) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { uint mode; uint count; uint width; } pc;

void run(uint i) {
  if (i >= pc.count) return;
  vec4 q = queries[i];
  if (pc.mode == 0u) {
    results[i] = textureLod(tex, vec3(q.x, q.y, q.z), q.w);
  } else {
    results[i] = texelFetch(tex, ivec3(floatBitsToInt(q.x), floatBitsToInt(q.y), floatBitsToInt(q.z)), floatBitsToInt(q.w));
  }
}

#ifdef STAGE_COMPUTE
layout(local_size_x = 64) in;
void main() { run(gl_GlobalInvocationID.x); }
#else
layout(location = 0) out vec4 color;
void main() {
  run(uint(gl_FragCoord.y) * pc.width + uint(gl_FragCoord.x));
  color = vec4(0.0);
}
#endif
