#include "inputs/material.h"

#include "util/pass_log.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "emu/format.h"
#include "util/image_io.h"
#include "passes/mips.h"
#include "lanes/instantiate.h"

namespace shadetwin {

std::vector<std::string> materialMapFiles(const Scene& scene) {
  std::vector<std::string> files;
  for (const Material& m : scene.materials)
    for (const std::string* f : {&m.diffuseMap, &m.specularMap, &m.roughnessMap})
      if (!f->empty() && std::find(files.begin(), files.end(), *f) == files.end()) files.push_back(*f);
  return files;
}

namespace {
uint32_t layerOf(const std::vector<std::string>& files, const std::string& f) {
  if (f.empty()) return 0;
  return uint32_t(std::find(files.begin(), files.end(), f) - files.begin()) + 1;
}

void setBrdf(MaterialGpu& g, const Material& m) {
  namespace sc = shade::scalar;
  g.lobe0[2] = g.lobe1[2] = 1.0f;  // absent lobes: axis +z, n = 1, rho = 0
  g.lobe0[3] = g.lobe1[3] = 1.0f;
  if (m.brdf == "phong") g.kind[0] = sc::kBrdfPhong, g.brdf[0] = m.exponent;
  else if (m.brdf == "blinn") g.kind[0] = sc::kBrdfBlinn, g.brdf[0] = m.exponent;
  else if (m.brdf == "ward") g.kind[0] = sc::kBrdfWard, g.brdf[1] = m.roughness, g.brdf[2] = m.roughnessY;
  else if (m.brdf == "ggx") g.kind[0] = sc::kBrdfGgx, g.brdf[1] = g.brdf[2] = m.roughness;
  else if (m.brdf == "lafortune") {
    if (m.lobes.empty() || m.lobes.size() > 2)
      throw std::invalid_argument("material '" + m.name + "': a lafortune BRDF needs 1 or 2 lobes");
    g.kind[0] = sc::kBrdfLafortune;
    float* lobes[2] = {g.lobe0, g.lobe1};
    for (size_t k = 0; k < m.lobes.size(); ++k) {
      std::memcpy(lobes[k], m.lobes[k].c.data(), 12);
      lobes[k][3] = m.lobes[k].n;
      g.rho[k] = m.lobes[k].rho;
    }
  } else {
    throw std::invalid_argument("material '" + m.name + "': BRDF '" + m.brdf +
                                "' cannot be importance-sampled by this technique (phong, blinn, ward, lafortune or ggx)");
  }
}
}  // namespace

std::vector<MaterialGpu> materialRecords(const Scene& scene, bool withBrdf) {
  const std::vector<Material> mats = scene.materials.empty() ? std::vector<Material>{Material{}} : scene.materials;
  const std::vector<std::string> files = materialMapFiles(scene);
  std::vector<MaterialGpu> out;
  for (const Material& m : mats) {
    if (!withBrdf && m.hasMaps())
      throw std::invalid_argument("material '" + m.name + "' has material maps, which technique " + scene.technique +
                                  " does not read (fis, unfiltered, stochastic and env do)");
    MaterialGpu g{};
    std::memcpy(g.diffuse, m.diffuse.data(), 12);
    std::memcpy(g.specular, m.specular.data(), 12);
    if (withBrdf) setBrdf(g, m);
    g.maps[0] = layerOf(files, m.diffuseMap);
    g.maps[1] = layerOf(files, m.specularMap);
    g.maps[2] = layerOf(files, m.roughnessMap);
    out.push_back(g);
  }
  return out;
}

uint32_t brdfKindsOf(const std::vector<MaterialGpu>& records) {
  uint32_t kinds = 0;
  for (const MaterialGpu& r : records) kinds |= 1u << r.kind[0];
  return kinds;
}

MaterialMapImages loadMaterialMaps(const Scene& scene) {
  const std::vector<std::string> files = materialMapFiles(scene);
  MaterialMapImages out;
  if (files.empty()) return out;
  out.texels.clear();
  out.layers = uint32_t(files.size());
  for (size_t i = 0; i < files.size(); ++i) {
    const ImageRGBA img = loadImageRGBA(files[i]);
    if (i == 0) out.width = img.width, out.height = img.height;
    if (img.width != out.width || img.height != out.height)
      throw FileError(files[i] + ": material map is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                      ", but " + files[0] + " is " + std::to_string(out.width) + "x" + std::to_string(out.height) +
                      " (the maps of a scene share one size: resample them, e.g. oiiotool IN --resize WxH -o OUT)");
    for (float v : img.texels)
      if (!std::isfinite(v)) throw FileError(files[i] + ": material map has a non-finite texel value");
    out.texels.insert(out.texels.end(), img.texels.begin(), img.texels.end());
  }
  return out;
}

double mapBilinear(const MaterialMapImages& m, uint32_t layer, double u, double v, int c) {
  const int64_t w = m.width, h = m.height;
  const double x = u * double(w) - 0.5, y = v * double(h) - 0.5, fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto texel = [&](int64_t i, int64_t j) {
    i = ((i % w) + w) % w, j = ((j % h) + h) % h;
    return double(m.texels[((size_t(layer) * size_t(h) + size_t(j)) * size_t(w) + size_t(i)) * 4 + size_t(c)]);
  };
  const int64_t i0 = int64_t(fx), j0 = int64_t(fy);
  return (1 - ay) * ((1 - ax) * texel(i0, j0) + ax * texel(i0 + 1, j0)) +
         ay * ((1 - ax) * texel(i0, j0 + 1) + ax * texel(i0 + 1, j0 + 1));
}

emu::Texture materialMapsEmu(const MaterialMapImages& m) {
  if (m.width > 1 || m.height > 1) notePass("mips");  // a device pass on the Vulkan build (mipChainGpu)
  return packTexture(emu::Format::RGBA32F, m.width, m.height, m.layers, mipChainCpu(m.texels, m.width, m.height, m.layers, 8));
}

emu::Texture materialMapsVulkan(vk::Context& ctx, const MaterialMapImages& m) {
  return packTexture(emu::Format::RGBA32F, m.width, m.height, m.layers, mipChainGpu(ctx, m.texels, m.width, m.height, m.layers));
}

}  // namespace shadetwin
