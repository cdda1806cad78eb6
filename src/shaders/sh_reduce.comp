#version 450
// SH irradiance, step 2 (shade/sh_irradiance.h): one invocation per coefficient k reduces the row
// sums by the pairwise tree (stride 1, 2, 4, ...; in place), then scales band l by A_l / pi (bands 0-2;
// band 3 stays raw). 16 coefficients per row.
// The C++ driver (inputs/sh_irradiance.cpp) walks the same tree.
#extension GL_GOOGLE_include_directive : require
#include "shade/all.inl"

layout(local_size_x = 16) in;
layout(std430, set = 0, binding = 0) buffer Rows { vec4 rows[]; };  // 16 per row
layout(std430, set = 0, binding = 1) writeonly buffer Out { vec4 sh[16]; };
layout(push_constant) uniform Push { uint rowCount; } pc;  // inputs/sh_irradiance.cpp

void main() {
  uint k = gl_GlobalInvocationID.x;
  if (k >= 16u) return;
  for (uint s = 1u; s < pc.rowCount; s *= 2u) {
    for (uint i = 0u; i + s < pc.rowCount; i += 2u * s) {
      vec4 a = rows[i * 16u + k];
      vec4 b = rows[(i + s) * 16u + k];
      rows[i * 16u + k] = vec4(shAdd3(vec3(a.x, a.y, a.z), vec3(b.x, b.y, b.z)), 0.0f);
    }
  }
  vec4 t = rows[k];
  sh[k] = vec4(shIrradianceScale(k, vec3(t.x, t.y, t.z)), 0.0f);
}
