// Shadow-map pass, vertex stage (the pass is depth-only: no fragment shader in either build).
// world = model * pos, clip = lightViewProj * world, both as ordered per-column sums (xformPoint),
// so the emulator's and the GPU's clip positions are the same floats.
// model: object -> world (columns m0..m3); light: world -> light clip space (columns l0..l3), an
// orthographic projection built on the host (passes/shadow.h shadowViewProjection).

Float4 shadowVertex(Float4 m0, Float4 m1, Float4 m2, Float4 m3, Float4 l0, Float4 l1, Float4 l2, Float4 l3, Float3 pos) {
  Float4 world = xformPoint(m0, m1, m2, m3, pos);
  return xformPoint(l0, l1, l2, l3, Float3(world.x, world.y, world.z));
}
