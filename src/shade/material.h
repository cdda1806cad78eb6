// Surface materials of the sampling techniques (fis and its baselines, env): a material record's
// constants, optionally modulated by material maps, give a pixel its diffuse and specular colours and
// its BRDF parameters. Shared by the GLSL entry points (shade_fis.comp, shade_env.comp) and the
// emulator (passes/shade_emu.cpp); the record layout is inputs/material.h's MaterialGpu.
//
// Maps: all of a scene's maps are layers of one 2D array texture (RGBA32F, full MIP chain, repeat
// addressing, trilinear). A record names a map by layer + 1 (0: no map). Lookups use textureLod at
// the LOD of the pixel's uv footprint, from the quad derivatives the G-buffer pass stored in G3,
// with Vulkan's isotropic scale factor (spec, "Scale Factor and Level-of-Detail"):
//   rho_x = |(du/dx w, dv/dx h)|, rho_y = |(du/dy w, dv/dy h)|, lambda = log2(max(rho_x, rho_y))
//         = 1/2 log2(max(rho_x^2, rho_y^2)),
// computed here with the exact-math layer, so both builds pass the sampler the same explicit LOD
// (a device's own textureGrad LOD arithmetic is implementation-defined; this one is not). lambda is
// clamped below at 0 (no footprint, e.g. the background: level 0).
// A diffuse / specular map multiplies the constant colour by its RGB; a roughness map multiplies the
// Ward alphas / GGX alpha by its red channel, kept >= kMinMapRoughness (alpha = 0 would make the
// sampled pdf 0/0).

const float kMinMapRoughness = 1.0e-4f;

struct SurfaceMaterial {
  Float3 diffuse;
  Float3 specular;
  BrdfParams brdf;
};

// BRDF parameters from a material record: brdf = (e, ax, ay, -), lobe_k = (Cx, Cy, Cz, n_k),
// rho = (rho_0, rho_1, -, -) (Lafortune; rho_k = 0 for an absent lobe).
BrdfParams brdfParamsPacked(Uint kind, Float4 brdf, Float4 lobe0, Float4 lobe1, Float4 rho) {
  return BrdfParams(kind, brdf.x, brdf.y, brdf.z, Float3(lobe0.x, lobe0.y, lobe0.z), lobe0.w, rho.x,
                    Float3(lobe1.x, lobe1.y, lobe1.z), lobe1.w, rho.y);
}

// LOD of a map of `size` texels for G3 = (du/dx, dv/dx, du/dy, dv/dy).
Float mapLod(Float4 g3, Float2 size) {
  PRECISE Float ux = g3.x * size.x;
  PRECISE Float vx = g3.y * size.y;
  PRECISE Float uy = g3.z * size.x;
  PRECISE Float vy = g3.w * size.y;
  PRECISE Float rx2 = ux * ux + vx * vx;
  PRECISE Float ry2 = uy * uy + vy * vy;
  PRECISE Float r2 = max(rx2, ry2);
  PRECISE Float l = 0.5f * exLog2(select(r2 > 0.0f, r2, 1.0f));
  return max(l, 0.0f);
}

// The pixel's material: the record's constants (diffuse, specular, brdf) modulated by its maps
// (layer + 1 each, 0: none) at uv = (G1.w, G2.w). A map no lane uses is not read.
SurfaceMaterial surfaceMaterial(Sampler2DArray maps, Float3 diffuse, Float3 specular, BrdfParams brdf, Uint diffuseMap,
                                Uint specularMap, Uint roughnessMap, Float4 g1, Float4 g2, Float4 g3) {
  SurfaceMaterial m = SurfaceMaterial(diffuse, specular, brdf);
  Mask used = (diffuseMap != 0u || specularMap != 0u) || roughnessMap != 0u;
  IF_ANY(used) {
    Float2 uv = Float2(g1.w, g2.w);
    Float lod = mapLod(g3, textureSizeOf(maps));
    Mask md = diffuseMap != 0u;
    IF_ANY(md) {
      Float4 t = textureLodLayer(maps, uv, Float(select(md, diffuseMap, Uint(1u)) - Uint(1u)), lod);
      PRECISE Float3 kd = diffuse * Float3(t.x, t.y, t.z);
      m.diffuse = select(md, kd, m.diffuse);
    }
    Mask ms = specularMap != 0u;
    IF_ANY(ms) {
      Float4 t = textureLodLayer(maps, uv, Float(select(ms, specularMap, Uint(1u)) - Uint(1u)), lod);
      PRECISE Float3 ks = specular * Float3(t.x, t.y, t.z);
      m.specular = select(ms, ks, m.specular);
    }
    Mask mr = roughnessMap != 0u;
    IF_ANY(mr) {
      Float4 t = textureLodLayer(maps, uv, Float(select(mr, roughnessMap, Uint(1u)) - Uint(1u)), lod);
      PRECISE Float ax = max(brdf.ax * t.x, kMinMapRoughness);
      PRECISE Float ay = max(brdf.ay * t.x, kMinMapRoughness);
      m.brdf.ax = select(mr, ax, m.brdf.ax);
      m.brdf.ay = select(mr, ay, m.brdf.ay);
    }
  }
  return m;
}
