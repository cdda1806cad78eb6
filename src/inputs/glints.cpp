#include "inputs/glints.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include "inputs/glint_tables.h"
#include "inputs/normal_map.h"
#include "inputs/sh_legendre.h"
#include "vk/context.h"

namespace shadetwin {

namespace {

}  // namespace

uint64_t glintShadeLoopBound(uint32_t order, uint32_t rings, uint32_t sectors, bool lobeTable) {
  const uint64_t M = order + 1, T = rings, P = sectors, G = (sectors + 7) / 8;
  const uint64_t perBin = lobeTable ? (M * M + 3) / 4 + 1 : M + M * (M + 1) / 2;
  return 2 * M * M + 2 * M + T + 9 * T * G + T * P * perBin;
}

NormalMap glintMaterialMap(const Material& m) {
  static const std::map<std::string, NormalMapKind> kinds{{"flat", NormalMapKind::Flat},
                                                          {"flakes", NormalMapKind::Flakes},
                                                          {"scratches", NormalMapKind::Scratches},
                                                          {"brushed", NormalMapKind::Brushed},
                                                          {"bumps", NormalMapKind::Bumps}};
  const auto k = kinds.find(m.glintMap);
  if (k == kinds.end()) return loadNormalMap(m.glintMap);
  NormalMapSpec s;
  s.kind = k->second, s.size = m.glintMapSize, s.seed = m.glintMapSeed, s.spread = m.glintSpread;
  s.cells = std::max(1u, s.size / 16);
  return generateNormalMap(s);
}

namespace {

// Everything but the lighting table (the same on both builds).
GlintInputs common(const Scene& scene, const emu::Texture& env) {
  GlintInputs in;
  in.bins = NdfBinningSpec{scene.glintRings, scene.glintSectors, scene.glintThetaMax};
  const auto t0 = std::chrono::steady_clock::now();
  // Distinct maps in order of first use; every material's rings -> layers of the one array.
  std::map<GlintMapKey, uint32_t> index;
  std::vector<NdfSat> sats;
  std::vector<uint32_t> mapOfMaterial(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const GlintMapKey key = glintMapKey(m);
    auto it = index.find(key);
    if (it == index.end()) {
      NormalMap nm;
      try {
        nm = glintMaterialMap(m);
      } catch (const std::exception& e) {
        throw std::invalid_argument("material '" + m.name + "': glints map: " + e.what());
      }
      if (!sats.empty() && (nm.width != sats[0].width || nm.height != sats[0].height))
        throw std::invalid_argument("material '" + m.name + "': its glints map is " + std::to_string(nm.width) + "x" +
                                    std::to_string(nm.height) + ", the scene's first is " + std::to_string(sats[0].width) + "x" +
                                    std::to_string(sats[0].height) + " (one texture array holds every map: use one size)");
      sats.push_back(buildNdfSat(nm, in.bins));
      it = index.emplace(key, uint32_t(sats.size() - 1)).first;
    }
    mapOfMaterial[i] = it->second;
  }
  in.maps = uint32_t(sats.size()), in.mapSize = sats[0].width;
  // One array: map k's stored rings after map k-1's.
  std::vector<uint32_t> base(sats.size(), 0);
  uint32_t layers = 0;
  for (size_t k = 0; k < sats.size(); ++k) base[k] = layers, layers += std::max(1u, sats[k].storedRings);
  const uint32_t G = ndfSatGroups(in.bins), tw = sats[0].width * G, th = sats[0].height;
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(size_t(tw) * th * layers * 16, 0));
  for (size_t k = 0; k < sats.size(); ++k) {
    const emu::Texture t = ndfSatTexture(sats[k]);
    std::memcpy(level[0].data() + size_t(base[k]) * tw * th * 16, t.levels()[0].data(), t.levels()[0].size());
    in.satBytes += sats[k].bytes();
  }
  in.sat = std::make_shared<emu::Texture>(emu::Format::RGBA32UI, tw, th, layers, std::move(level));
  in.satMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // Bin directions.
  std::vector<float> bd(size_t(in.bins.rings) * in.bins.sectors * 4, 0.0f);
  for (uint32_t r = 0; r < in.bins.rings; ++r)
    for (uint32_t p = 0; p < in.bins.sectors; ++p) {
      const reference::D3 d = ndfBinDirection(in.bins, r, p);
      float* o = &bd[(size_t(r) * in.bins.sectors + p) * 4];
      o[0] = float(d.x), o[1] = float(d.y), o[2] = float(d.z);
    }
  in.binDirs = std::make_shared<emu::Texture>(emu::floatTexture(emu::Format::RGBA32F, in.bins.sectors, in.bins.rings, bd.data()));
  // The shading degree: the table's, cut at the largest band limit of the lobes.
  uint32_t band = 0;
  for (const Material& m : scene.materials) band = std::max(band, gaussianLobeBandLimit(m.glintSigma, 1e-6, scene.glintOrder));
  in.order = std::min(scene.glintOrder, band);
  // Material rows: (eta, sigma), (k, texels per uv), 16 ring layers (-1: none) 4 per texel, then
  // the lobe's zonal factor k_l (0 beyond the lobe's band limit M_NDF) for l = 0 .. order in .x,
  // M_NDF itself in texel 6's .y.
  const uint32_t mw = 6 + in.order + 1;
  std::vector<float> mt(size_t(mw) * scene.materials.size() * 4, 0.0f);
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    float* row = &mt[i * mw * 4];
    row[0] = m.glintEta[0], row[1] = m.glintEta[1], row[2] = m.glintEta[2], row[3] = m.glintSigma;
    row[4] = m.glintK[0], row[5] = m.glintK[1], row[6] = m.glintK[2], row[7] = float(double(in.mapSize) * m.glintScale);
    const NdfSat& sat = sats[mapOfMaterial[i]];
    for (uint32_t r = 0; r < 16; ++r)
      row[8 + r] = r < in.bins.rings && sat.slot[r] >= 0 ? float(base[mapOfMaterial[i]] + uint32_t(sat.slot[r])) : -1.0f;
    const std::vector<double> z = gaussianLobeZh(m.glintSigma, in.order);
    const uint32_t lim = gaussianLobeBandLimit(m.glintSigma, 1e-6, in.order);
    in.lobeBandLimits.push_back(lim);
    for (uint32_t l = 0; l <= in.order; ++l)
      row[(6 + l) * 4] = l <= lim ? float(z[l] * std::sqrt(4 * std::numbers::pi / (2.0 * l + 1))) : 0.0f;
    row[6 * 4 + 1] = float(lim);
  }
  in.materials = std::make_shared<emu::Texture>(emu::floatTexture(emu::Format::RGBA32F, mw, uint32_t(scene.materials.size()), mt.data()));
  in.coef = std::make_shared<emu::Texture>(shLegendreCoefficients(std::max(1u, in.order)));
  in.lobeRings = scene.glintLobeRings, in.lobeSectors = scene.glintLobeSectors;
  const auto tl = std::chrono::steady_clock::now();
  if (in.lobeRings) {
    in.lobes = std::make_shared<emu::Texture>(glintLobeTable(in.order, in.lobeRings, in.lobeSectors));
    in.lobeBytes = in.lobes->levels()[0].size();
  } else {
    const float zero[4] = {0, 0, 0, 0};
    in.lobes = std::make_shared<emu::Texture>(emu::floatTexture(emu::Format::RGBA32F, 1, 1, zero));
  }
  in.lobeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - tl).count();
  // The lighting table's spec: the smallest environment level at least 3 (order + 1) texels wide.
  in.lightingSpec.order = in.order, in.lightingSpec.rings = scene.glintViewRings, in.lightingSpec.sectors = scene.glintViewSectors;
  in.lightingSpec.level = 0;
  while (in.lightingSpec.level + 1 < env.levelCount() && env.levelWidth(in.lightingSpec.level + 1) >= 3 * (in.order + 1))
    ++in.lightingSpec.level;
  return in;
}

// The table as the shading pass reads it: each view's lighting band limit M_light at 1e-6 in the
// alpha of its coefficient 0.
void attachLighting(GlintInputs& in, const GlintLightingTable& t) {
  std::vector<float> rgba = t.rgba;
  in.lightBandLimits = glintLightBandLimits(t, 1e-6);
  for (size_t v = 0; v < in.lightBandLimits.size(); ++v) rgba[v * t.coeffs * 4 + 3] = float(in.lightBandLimits[v]);
  in.lighting = std::make_shared<emu::Texture>(emu::floatTexture(emu::Format::RGBA32F, t.coeffs, t.spec.rings * t.spec.sectors, rgba.data()));
  in.lightingBytes = t.bytes(), in.lightingMs = t.buildMs;
}

// The lighting table's bands for the device the inputs are built for (its loop limit).
void bands(GlintInputs& in, const emu::Texture& env, const emu::DeviceProfile& dev) {
  in.lightingSpec.bandRows = glintBandRows(dev.loopIterationLimit, env.levelWidth(in.lightingSpec.level),
                                           env.levelHeight(in.lightingSpec.level), in.lightingSpec.order);
}

}  // namespace

GlintInputs glintInputsEmu(const Scene& scene, const emu::Texture& env, const emu::DeviceProfile& dev) {
  GlintInputs in = common(scene, env);
  bands(in, env, dev);
  attachLighting(in, glintLightingEmu(env, dev, in.lightingSpec));
  return in;
}

GlintInputs glintInputsVulkan(vk::Context& ctx, const Scene& scene, const emu::Texture& env) {
  GlintInputs in = common(scene, env);
  bands(in, env, emu::profileForDevice(ctx.deviceName()));
  attachLighting(in, glintLightingVulkan(ctx, env, in.lightingSpec));
  return in;
}

}  // namespace shadetwin
