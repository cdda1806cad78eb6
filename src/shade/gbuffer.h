// G-buffer pass (vertex and fragment halves), shared by the Vulkan build (src/shaders/gbuffer.vert,
// gbuffer.frag) and the emulator (src/passes/gbuffer.cpp). Matrices arrive as columns; every
// product is an explicit, ordered sum of per-column products, so both builds round identically.
//
// Layout of the four RGBA32F attachments (docs/DESIGN.md "G-buffer"):
//   G0 = world position xyz, w = (material id + 1) * handedness   (0: no geometry)
//   G1 = world normal xyz (interpolated, not renormalised), w = u
//   G2 = world tangent xyz (interpolated), w = v
//   G3 = (du/dx, dv/dx, du/dy, dv/dy) from the 2x2 quad

Float4 xformPoint(Float4 c0, Float4 c1, Float4 c2, Float4 c3, Float3 p) {
  PRECISE Float4 r = c0 * p.x;
  r = r + c1 * p.y;
  r = r + c2 * p.z;
  r = r + c3;
  return r;
}

Float3 xformDir(Float4 c0, Float4 c1, Float4 c2, Float3 d) {
  PRECISE Float3 r = Float3(c0.x, c0.y, c0.z) * d.x;
  r = r + Float3(c1.x, c1.y, c1.z) * d.y;
  r = r + Float3(c2.x, c2.y, c2.z) * d.z;
  return r;
}

struct GbufVertex {
  Float4 clip;
  Float3 worldPos;
  Float3 normal;
  Float4 tangent;
  Float2 uv;
};

// model: object -> world (columns m0..m3); nrm: its inverse transpose (columns n0..n2);
// vp: world -> clip (columns v0..v3).
GbufVertex gbufferVertex(Float4 m0, Float4 m1, Float4 m2, Float4 m3, Float4 n0, Float4 n1, Float4 n2, Float4 v0,
                         Float4 v1, Float4 v2, Float4 v3, Float3 pos, Float3 normal, Float4 tangent, Float2 uv) {
  Float4 world = xformPoint(m0, m1, m2, m3, pos);
  Float3 w3 = Float3(world.x, world.y, world.z);
  Float3 t = xformDir(m0, m1, m2, Float3(tangent.x, tangent.y, tangent.z));
  return GbufVertex(xformPoint(v0, v1, v2, v3, w3), w3, xformDir(n0, n1, n2, normal),
                    Float4(t.x, t.y, t.z, tangent.w), uv);
}

struct GbufTexels {
  Float4 g0;
  Float4 g1;
  Float4 g2;
  Float4 g3;
};

// Material slot of a G-buffer pixel: G0.w = (id + 1) * handedness, 0 for no geometry (slot 0 then),
// clamped to the material table's last entry. Used by the shading passes of both builds.
Uint materialSlot(Float g0w, Uint materialCount) {
  Uint id = select(g0w == 0.0f, Uint(0u), Uint(abs(g0w)) - 1u);
  return min(id, materialCount - 1u);
}

// duvdx / duvdy: the quad derivatives dFdx(uv) / dFdy(uv) of the stage.
GbufTexels gbufferFragment(Float3 worldPos, Float3 normal, Float4 tangent, Float2 uv, Float2 duvdx, Float2 duvdy,
                           Float materialId) {
  PRECISE Float id = materialId + 1.0f;
  id = select(tangent.w < 0.0f, -id, id);
  return GbufTexels(Float4(worldPos.x, worldPos.y, worldPos.z, id), Float4(normal.x, normal.y, normal.z, uv.x),
                    Float4(tangent.x, tangent.y, tangent.z, uv.y), Float4(duvdx.x, duvdx.y, duvdy.x, duvdy.y));
}
