#version 450
// verify ndf (issue 17): the NDF histogram's box counts (shade/ndf_histogram.h ndfBoxCounts8) from
// the SAT texture, one invocation per box, local size 64; writes, per box, every stored ring's
// groups of 8 packed counts. Tail invocations compute the last box again and store nothing.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform usampler2DArray sat;  // RGBA32UI (inputs/ndf_histogram.h ndfSatTexture)
layout(std430, set = 0, binding = 1) readonly buffer Boxes { ivec4 boxes[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Out { uvec4 counts[]; };
layout(push_constant) uniform Push {
  uint count, layers, groups, width, height;
  float invW, invH;
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  uint b = min(i, pc.count - 1u);
  ivec4 box = boxes[b];
  for (int layer = 0; layer < int(pc.layers); ++layer)
    for (int g = 0; g < int(pc.groups); ++g) {
      UintTexel4 c = ndfBoxCounts8(sat, layer, g, int(pc.groups), int(pc.width), int(pc.height), pc.invW, pc.invH, box.x,
                                   box.y, box.z, box.w);
      if (i < pc.count) counts[(i * pc.layers + uint(layer)) * pc.groups + uint(g)] = uvec4(c.x, c.y, c.z, c.w);
    }
}
