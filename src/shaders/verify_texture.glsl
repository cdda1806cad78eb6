#version 450
// Entry point of `shadetwin verify texture`: one textureLod (mode 0), texelFetch (mode 1) or, in the
// fragment stage, implicit-LOD texture() (mode 2) per invocation; query = (u, v, layer, lod), or the
// int bits of (x, y, layer, level) for texelFetch. Mode 2 ignores the query's lod: the LOD comes from
// the quad's derivatives of (u, v), so neighbouring pixels' queries must be coherent.
layout(set = 0, binding = 0) uniform sampler2DArray tex;
layout(std430, set = 0, binding = 1) readonly buffer Queries { vec4 queries[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Results { vec4 results[]; };
layout(push_constant) uniform Push { uint mode; uint count; uint width; } pc;

void run(uint i) {
  if (i >= pc.count) return;
  vec4 q = queries[i];
  if (pc.mode == 0u) {
    results[i] = textureLod(tex, vec3(q.x, q.y, q.z), q.w);
#ifdef STAGE_FRAGMENT
  } else if (pc.mode == 2u) {
    results[i] = texture(tex, vec3(q.x, q.y, q.z));
#endif
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
