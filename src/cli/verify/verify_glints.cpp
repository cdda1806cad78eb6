// `shadetwin verify ndf` (issue 17): the NDF histogram's box counts, read from the SAT texture by the
// shared lookup on the Vulkan device (src/shaders/ndf_counts.comp) and on the emulator's 8-lane
// build, against the host's exact counts (inputs/ndf_histogram.h ndfBoxCounts).
#include <cstring>
#include <iostream>
#include <random>

#include "cli/verify/verify.h"
#include "inputs/ndf_histogram.h"
#include "inputs/normal_map.h"
#include "lanes/instantiate.h"
#include "passes/passes_vk.h"
#include "vk/context.h"

namespace shadetwin {

namespace {
#include "ndf_counts_comp.inc"

struct NdfPush {
  uint32_t count, layers, groups, width, height;
  float invW, invH;
};
static_assert(sizeof(NdfPush) == 28, "NdfPush must match the push block of ndf_counts.comp");
}  // namespace

int verifyNdf(const VerifyOptions& opts, std::ostream& out) {
  NormalMapSpec spec;
  spec.kind = normalMapKind(opts.mapKind);
  spec.size = opts.mapSize;
  spec.seed = uint32_t(opts.seed);
  spec.cells = std::max(1u, spec.size / 16);
  spec.spread = 0.4f;  // wide enough to use several rings
  const NormalMap map = generateNormalMap(spec);
  const NdfBinningSpec bins;
  const NdfSat sat = buildNdfSat(map, bins);
  const emu::Texture tex = ndfSatTexture(sat);
  const uint32_t groups = ndfSatGroups(bins), layers = sat.storedRings, n = uint32_t(opts.count);
  out << "verify ndf: " << normalMapKindName(spec.kind) << " " << spec.size << "^2 (seed " << spec.seed << "), " << bins.rings
      << " x " << bins.sectors << " bins, " << layers << " rings stored, " << n << " boxes (up to 255 x 255 texels, anywhere "
      << "on the tiled map)\n";
  // Boxes: a quarter single texels, the rest random sizes, corners anywhere within +-4 map sizes.
  std::mt19937 rng(uint32_t(opts.seed));
  std::uniform_int_distribution<int> pos(-4 * int(spec.size), 4 * int(spec.size)), side(1, 255);
  std::vector<int32_t> boxes(4 * size_t(n));
  for (uint32_t i = 0; i < n; ++i) {
    const int x0 = pos(rng), y0 = pos(rng), w = i % 4 ? side(rng) : 1, h = i % 4 ? side(rng) : 1;
    boxes[4 * i] = x0, boxes[4 * i + 1] = y0, boxes[4 * i + 2] = x0 + w - 1, boxes[4 * i + 3] = y0 + h - 1;
  }
  const size_t values = size_t(n) * layers * groups * 4;
  const float invW = 1.0f / float(map.width), invH = 1.0f / float(map.height);
  // Host: the exact counts, packed as the lookup packs them.
  std::vector<uint32_t> host(values, 0), emuOut(values, 0);
  std::vector<uint32_t> c(size_t(bins.rings) * bins.sectors);
  for (uint32_t i = 0; i < n; ++i) {
    ndfBoxCounts(sat, boxes[4 * i], boxes[4 * i + 1], boxes[4 * i + 2], boxes[4 * i + 3], c.data());
    for (uint32_t t = 0; t < bins.rings; ++t) {
      if (sat.slot[t] < 0) continue;
      for (uint32_t p = 0; p < bins.sectors; ++p)
        host[((size_t(i) * layers + uint32_t(sat.slot[t])) * groups + p / 8) * 4 + (p % 8) / 2] |= c[size_t(t) * bins.sectors + p]
                                                                                                    << (16 * (p % 2));
    }
  }
  // Emulator: the 8-lane build, 8 boxes per vector (the tail repeats the last box).
  namespace x8 = shade::x8;
  const shade::USampler2DArray s{&tex};
  for (uint32_t i0 = 0; i0 < n; i0 += 8) {
    emu::I32<8> X0, Y0, X1, Y1;
    for (int l = 0; l < 8; ++l) {
      const uint32_t b = std::min(n - 1, i0 + uint32_t(l));
      X0.set(l, boxes[4 * b]), Y0.set(l, boxes[4 * b + 1]), X1.set(l, boxes[4 * b + 2]), Y1.set(l, boxes[4 * b + 3]);
    }
    for (uint32_t layer = 0; layer < layers; ++layer)
      for (uint32_t g = 0; g < groups; ++g) {
        const x8::UintTexel4 v = x8::ndfBoxCounts8(s, int(layer), int(g), int(groups), int(map.width), int(map.height), invW, invH,
                                                   X0, Y0, X1, Y1);
        for (int l = 0; l < 8 && i0 + uint32_t(l) < n; ++l) {
          uint32_t* o = &emuOut[((size_t(i0 + uint32_t(l)) * layers + layer) * groups + g) * 4];
          o[0] = v.x[l], o[1] = v.y[l], o[2] = v.z[l], o[3] = v.w[l];
        }
      }
  }
  // Vulkan.
  vk::Context ctx(vk::ContextOptions{opts.device, opts.validate});
  out << "device: " << ctx.deviceName() << "\n";
  vk::Image img(ctx, VK_FORMAT_R32G32B32A32_UINT, tex.width(), tex.height(), tex.layers(), tex.levels(), 16);
  vk::Sampler sampler(ctx, dataTextureSamplerInfo());
  vk::Buffer boxBuf(ctx, boxes.size() * 4), outBuf(ctx, values * 4);
  std::memcpy(boxBuf.as<int32_t>(), boxes.data(), boxes.size() * 4);
  static constexpr VkDescriptorType kTypes[3] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                 VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel kernel(ctx, vk::Stage::Compute, kSpv_ndf_counts_comp, kTypes, sizeof(NdfPush));
  const NdfPush push{n, layers, groups, map.width, map.height, invW, invH};
  const vk::Binding b[3] = {{kTypes[0], VK_NULL_HANDLE, img.view(), sampler.handle()}, {kTypes[1], boxBuf.handle()},
                            {kTypes[2], outBuf.handle()}};
  kernel.run(b, &push, n);
  const uint32_t* gpu = outBuf.as<uint32_t>();
  size_t emuSame = 0, gpuSame = 0;
  for (size_t k = 0; k < values; ++k) emuSame += emuOut[k] == host[k], gpuSame += gpu[k] == host[k];
  out << "  emulator (8 lanes) = host: " << emuSame << "/" << values << "\n";
  out << "  vulkan = host:             " << gpuSame << "/" << values << "\n";
  const bool ok = emuSame == values && gpuSame == values && ctx.validationErrors() == 0;
  UlpTally emuCase{"emulator (8 lanes) = host"}, gpuCase{"vulkan = host"};
  emuCase.identical = emuSame, emuCase.total = values, gpuCase.identical = gpuSame, gpuCase.total = values;
  writeVerifyReports(opts, {"ndf", ctx.deviceName(), "", 0, {emuCase, gpuCase}, ctx.validationErrors(), ctx.lastValidationMessage}, out);
  out << "ndf: " << (ok ? values : std::min(emuSame, gpuSame)) << "/" << values << (ok ? " bit-identical\n" : " differ\n");
  return ok ? 0 : 1;
}

}  // namespace shadetwin
