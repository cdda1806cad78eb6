#version 450
// `shadetwin calibrate`'s per-workgroup kernel (issue 19): nothing per invocation, in a module of its own. SwiftShader's
// setup of a workgroup grows with the module it runs, even where none of the code runs (calibrate.comp's empty kind
// read 33 us per workgroup in that module of 102K words, 0.9 us in a module of 4K; docs/RESULTS.md session 22), so
// the base cost is read from the smallest module. Not shared shading code: a thin measuring kernel of the host.
layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 2) writeonly buffer Dst { vec4 dst[]; };  // calibrate.comp's layout (its dst)
layout(push_constant) uniform Push { uint kind, iters, count, pad; float c, lod, step, pad2; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count && pc.c < 0.0) dst[0] = vec4(pc.c);  // never taken (c > 0): keeps the buffer and the push constants
}
