// verify texture: random textureLod / texelFetch lookups on random textures, per format x filter x
// address mode x shader stage, through the emulator (the device's profile) and the Vulkan build.
#include <cmath>
#include <cstring>
#include <iomanip>
#include <memory>
#include <ostream>
#include <random>
#include <stdexcept>
#include <vector>

#include "emu/device_profile.h"
#include "emu/raster.h"
#include "emu/sampler.h"
#include "util/image_io.h"
#include "passes/mips.h"
#include "cli/verify/verify.h"
#include "vk/context.h"

namespace shadetwin {

namespace {
#include "fullscreen_vert.inc"
#include "verify_texture_comp.inc"
#include "verify_texture_frag.inc"

VkFormat vkFormat(emu::Format f) {
  switch (f) {
    case emu::Format::RGBA32F:
      return VK_FORMAT_R32G32B32A32_SFLOAT;
    case emu::Format::RGBA16F:
      return VK_FORMAT_R16G16B16A16_SFLOAT;
    case emu::Format::RGBA8_UNORM:
      return VK_FORMAT_R8G8B8A8_UNORM;
    default:
      return VK_FORMAT_R32_SFLOAT;
  }
}
VkFilter vkFilter(emu::Filter f) { return f == emu::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }
VkSamplerAddressMode vkAddress(emu::AddressMode a) {
  switch (a) {
    case emu::AddressMode::ClampToEdge:
      return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case emu::AddressMode::Repeat:
      return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    default:
      return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
  }
}

// A random float texel value: mostly in [-2, 2], some outside [0, 1) by far, a few inf/NaN/denormal.
float randomValue(std::mt19937& rng, bool finite) {
  uint32_t pick = rng() % 1000;
  if (finite && pick < 4) pick = 500;  // --finite: no inf, NaN or denormal texels
  if (pick == 0) return INFINITY;
  if (pick == 1) return -INFINITY;
  if (pick == 2) return NAN;
  if (pick == 3) return 1e-39f;  // denormal
  if (pick < 20) return std::ldexp(float(rng() % 2000) - 1000.0f, int(rng() % (finite ? 6 : 40)) - 10);
  return std::uniform_real_distribution<float>(-2.0f, 2.0f)(rng);
}

// A texture of random size, layers and levels and random texels. Unless finite, one texture in four
// has one level of only +-inf texels: every lane that reads it with a mip weight of 0 returns inf
// alone but NaN from a level lerp, so it shows each lane's share in its vector's lerp decision.
emu::Texture randomTexture(emu::Format fmt, std::mt19937& rng, bool finite) {
  static const uint32_t sizes[] = {1, 2, 3, 4, 5, 7, 8, 13, 16, 31, 32, 37, 64, 100};
  uint32_t w = sizes[rng() % 14], h = sizes[rng() % 14], layers = 1 + rng() % 3;
  uint32_t full = emu::Texture::fullChainLevels(w, h);
  uint32_t levels = (rng() % 3 == 0) ? 1 + rng() % full : full;
  const uint32_t tb = emu::formatInfo(fmt).texelBytes;
  const uint32_t infLevel = !finite && levels > 1 && rng() % 4 == 0 ? rng() % levels : levels;
  std::vector<std::vector<uint8_t>> data(levels);
  for (uint32_t l = 0; l < levels; ++l) {
    uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
    data[l].resize(size_t(lw) * lh * layers * tb);
    uint8_t* p = data[l].data();
    auto value = [&] { return l == infLevel ? ((rng() & 1) ? INFINITY : -INFINITY) : randomValue(rng, finite); };
    for (size_t t = 0; t < size_t(lw) * lh * layers; ++t, p += tb) {
      switch (fmt) {
        case emu::Format::RGBA32UI: break;  // not a sampled format (kAllFormats)
        case emu::Format::RGBA32F:
        case emu::Format::R32F:
          for (uint32_t c = 0; c < tb / 4; ++c) {
            float v = value();
            std::memcpy(p + 4 * c, &v, 4);
          }
          break;
        case emu::Format::RGBA16F:
          for (int c = 0; c < 4; ++c) {
            uint16_t hv = emu::floatToHalf(value());
            std::memcpy(p + 2 * c, &hv, 2);
          }
          break;
        case emu::Format::RGBA8_UNORM:
          for (int c = 0; c < 4; ++c) p[c] = uint8_t(rng());
          break;
      }
    }
  }
  return emu::Texture(fmt, w, h, layers, std::move(data));
}

// Coordinates that hit the interesting places: texel centres and edges, outside [0, 1), negative.
float randomCoord(std::mt19937& rng, uint32_t size) {
  uint32_t pick = rng() % 8;
  float k = float(int(rng() % (4 * size + 1)) - int(size));
  if (pick == 0) return (k + 0.5f) / float(size);
  if (pick == 1) return k / float(size);
  return std::uniform_real_distribution<float>(-1.5f, 2.5f)(rng);
}

float randomLod(std::mt19937& rng, uint32_t levels) {
  uint32_t pick = rng() % 6;
  if (pick == 0) return float(int(rng() % (levels + 3)) - 1);         // integral
  if (pick == 1) return float(int(rng() % (levels + 3)) - 1) + 0.5f;  // ties
  return std::uniform_real_distribution<float>(-2.0f, float(levels) + 1.0f)(rng);
}

/// Coherent coordinates for implicit-LOD texture(): per aligned 16 x 16 block of the 1024-wide
/// fragment target, an affine map of the pixel position (random scale 2^-4 .. 2^6 texels per pixel,
/// rotation, anisotropy up to 4) plus a small quadratic term, and one random layer. One block in
/// eight is exact instead: a 45-degree map with a power-of-two step 2^-p per pixel from a dyadic
/// origin, so every coordinate and derivative is exact and rho^2 lands on exact powers of two, where
/// the LOD sits on a rounding tie (rho^2 = 2^(2k+1): LOD k + 1/2) for square power-of-two textures.
void smoothQueries(std::mt19937& rng, const emu::Texture& tex, std::vector<float>& q, size_t n) {
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  const size_t rowLen = 1024, blocksPerRow = rowLen / 16, blocks = blocksPerRow * ((n / rowLen + 15) / 16);
  struct Map {
    float u0, v0, a, b, c, d, k, layer;
  };
  std::vector<Map> maps(blocks);
  for (auto& m : maps) {
    if (rng() % 8 == 0) {
      const int p = int(std::ilogb(float(tex.width()))) + int(rng() % 11) - 6;  // 2^-6 .. 2^4 texels per pixel
      const float step = std::ldexp(1.0f, -p);
      m = {float(int(rng() % 128)) / 64.0f - 0.5f, float(int(rng() % 128)) / 64.0f - 0.5f, step, step, step, -step, 0.0f,
           float(rng() % tex.layers())};
      continue;
    }
    const float scale = std::exp2(-4.0f + 10.0f * U(rng)) / float(tex.width());
    const float aniso = 1.0f + 3.0f * U(rng), th = 6.2831853f * U(rng);
    m = {U(rng) * 2.0f - 0.5f,
         U(rng) * 2.0f - 0.5f,
         scale * std::cos(th),
         -scale * aniso * std::sin(th),
         scale * std::sin(th),
         scale * aniso * std::cos(th),
         scale * 0.05f * (U(rng) - 0.5f),
         float(rng() % tex.layers())};
  }
  for (size_t i = 0; i < n; ++i) {
    const size_t x = i % rowLen, y = i / rowLen;
    const Map& m = maps[(y / 16) * blocksPerRow + x / 16];
    const float fx = float(x % 16), fy = float(y % 16);
    q[4 * i] = m.u0 + m.a * fx + m.b * fy + m.k * fx * fy;
    q[4 * i + 1] = m.v0 + m.c * fx + m.d * fy - m.k * fx * fx;
    q[4 * i + 2] = m.layer;
    q[4 * i + 3] = 0.0f;
  }
}

/// The LOD each lane's texture() gets: the device's implicit LOD of its 2x2 quad (the profile's
/// per-quad model), in the lane's run: the lanes of the quad that the run's primitive does not cover
/// are masked, their buffer loads return 0, so their coordinates count as 0 in the derivatives.
void implicitLods(const emu::Texture& tex, const emu::SamplerDesc& sd, const emu::DeviceProfile& dev, const std::vector<float>& q,
                  const std::vector<uint32_t>& primitiveOf, const std::vector<emu::FragmentLane>& lanes,
                  std::vector<float>& out, size_t n) {
  const size_t rowLen = 1024;
  for (size_t k = 0; k < lanes.size(); ++k) {
    const size_t i = lanes[k].pixel, x = i % rowLen & ~size_t(1), y = i / rowLen & ~size_t(1);
    const size_t p[4] = {y * rowLen + x, y * rowLen + x + 1, (y + 1) * rowLen + x, (y + 1) * rowLen + x + 1};
    float s[4], t[4];
    for (int c = 0; c < 4; ++c) {
      const bool live = p[c] < n && primitiveOf[p[c]] == lanes[k].primitive;
      s[c] = live ? q[4 * p[c]] : 0.0f;
      t[c] = live ? q[4 * p[c] + 1] : 0.0f;
    }
    out[4 * k + 3] = emu::implicitLod(tex, sd, dev, s, t);
  }
}

struct FilterCase {
  const char* name;
  emu::Filter mag, min;
  emu::MipmapMode mip;
};
const FilterCase kFilters[] = {
    {"nearest", emu::Filter::Nearest, emu::Filter::Nearest, emu::MipmapMode::Nearest},
    {"nearest-miplin", emu::Filter::Nearest, emu::Filter::Nearest, emu::MipmapMode::Linear},
    {"bilinear", emu::Filter::Linear, emu::Filter::Linear, emu::MipmapMode::Nearest},
    {"trilinear", emu::Filter::Linear, emu::Filter::Linear, emu::MipmapMode::Linear},
    {"magN-minL", emu::Filter::Nearest, emu::Filter::Linear, emu::MipmapMode::Linear},
};
const emu::AddressMode kAddress[] = {emu::AddressMode::ClampToEdge, emu::AddressMode::Repeat,
                                     emu::AddressMode::MirroredRepeat};

}  // namespace

int verifyTexture(const VerifyOptions& opts, std::ostream& out) {
  vk::Context ctx({opts.device, opts.validate});
  emu::DeviceProfile profile = emu::profileForDevice(ctx.deviceName());
  out << "device: " << ctx.deviceName() << " (profile " << profile.name << (profile.verified ? "" : ", unverified")
      << ")\n";
  for (const std::string& kv : opts.profileSet) {  // alternative models: what the profile's choice is worth
    emu::setProfileField(profile, kv);
    out << "profile override: " << kv << " (emulator now follows " << profile.name << ")\n";
  }
  const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel comp(ctx, vk::Stage::Compute, kSpv_verify_texture_comp, layout, 12);
  vk::Kernel frag(ctx, vk::Stage::Fragment, kSpv_verify_texture_frag, layout, 12, kSpv_fullscreen_vert);
  // Whole SIMD vectors only: lanes past the end would be masked off on the device but still take part
  // in its per-vector sampler decisions with undefined coordinates. Two rows of the 1024-wide
  // fragment target... four rows: whole 4x4 stamps (rows of a stamp past the target still run).
  const size_t n = (opts.count + 4095) / 4096 * 4096;
  vk::Buffer qBuf(ctx, n * 16), rBuf(ctx, n * 16);
  std::vector<float> q(4 * n), emuOut(4 * n), gpu(4 * n);
  uint64_t identical = 0, total = 0;
  std::unique_ptr<ImageRGBA> image;
  std::unique_ptr<std::vector<std::vector<float>>> imageChain;
  if (!opts.image.empty()) {
    image = std::make_unique<ImageRGBA>(loadImageRGBA(opts.image));
    imageChain =
        std::make_unique<std::vector<std::vector<float>>>(mipChainCpu(image->texels, image->width, image->height, 1));
    out << "image: " << opts.image << " (" << image->width << "x" << image->height << ", " << imageChain->size()
        << " levels from the shared MIP kernel)\n";
  }
  // The SIMD vector each work item runs in on the device: compute item i = invocation i; fragment item
  // i = pixel (i % 1024, i / 1024) of the kernel's target. Lavapipe clips the full-screen triangle to
  // the viewport and fans the rectangle into two triangles along the diagonal (0,0)-(W,H) (measured
  // with a NaN probe; DeviceProfile::Raster::fansClippedPolygons), a block crossing it is shaded once per
  // triangle (emu::fragmentLanes); SwiftShader rasterizes the clipped polygon as one primitive. Masked
  // lanes load zeros (explicit LOD 0; implicit: their quad's LOD in that run, see implicitLods): the
  // emulator runs them as the extra lanes past n and discards their results.
  const uint32_t rowLen = 1024, rows = uint32_t((n + rowLen - 1) / rowLen);
  std::vector<uint32_t> computeVectors(n), primitiveOf(n);
  for (size_t i = 0; i < n; ++i) {
    computeVectors[i] = uint32_t(i / uint32_t(profile.computeVectorLanes));
    const double x = double(i % rowLen) + 0.5, y = double(i / rowLen) + 0.5;
    primitiveOf[i] = profile.raster.fansClippedPolygons && x * rows > y * rowLen ? 1u : 0u;
  }
  const std::vector<emu::FragmentLane> fragLanes = emu::fragmentLanes(profile, rowLen, rows, primitiveOf.data(), 2);
  std::vector<uint32_t> fragVectors(fragLanes.size());
  for (size_t k = 0; k < fragLanes.size(); ++k) fragVectors[k] = fragLanes[k].vector;
  std::vector<float> qFrag, outFrag;
  out << std::left << std::setw(8) << "format" << std::setw(16) << "filter" << std::setw(8) << "address"
      << std::setw(10) << "stage" << std::right << std::setw(22) << "identical/total" << std::setw(10) << "max ulp"
      << "\n";
  // --seeds N: seeds seed .. seed + N - 1 in one process; rows only for configurations that differ.
  for (uint64_t seed = opts.seed; seed < opts.seed + opts.seeds; ++seed) {
    std::mt19937 rng{uint32_t(seed)};
    const uint64_t seedIdentical = identical, seedTotal = total;
    for (emu::Format fmt : emu::kAllFormats) {
      for (int fi = -1; fi < int(std::size(kFilters)); ++fi) {  // -1: texelFetch
        for (emu::AddressMode am : kAddress) {
          if (fi < 0 && am != emu::AddressMode::ClampToEdge) continue;
          const std::string caseName = fi < 0 ? "texelFetch" : kFilters[fi].name;
          if (!opts.filters.empty() && ("," + opts.filters + ",").find("," + caseName + ",") == std::string::npos)
            continue;
          emu::Texture tex = image ? packTexture(fmt, image->width, image->height, 1, *imageChain)
                                   : randomTexture(fmt, rng, opts.finiteTexels);
          vk::Image image(ctx, vkFormat(fmt), tex.width(), tex.height(), tex.layers(), tex.levels(),
                          emu::formatInfo(fmt).texelBytes);
          emu::SamplerDesc sd;
          if (fi >= 0) {
            sd.magFilter = kFilters[fi].mag;
            sd.minFilter = kFilters[fi].min;
            sd.mipmapMode = kFilters[fi].mip;
          }
          sd.addressU = sd.addressV = am;
          sd.lodPerQuad = opts.implicitLod;
          switch (rng() % 4) {  // sampler LOD state: bias, min/max clamps
            case 1:
              sd.lodBias = (rng() & 1) ? 0.75f : -1.25f;
              break;
            case 2:
              sd.minLod = 0.5f;
              sd.maxLod = 2.25f;
              break;
            default:
              break;
          }
          VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
          si.magFilter = vkFilter(sd.magFilter);
          si.minFilter = vkFilter(sd.minFilter);
          si.mipmapMode = sd.mipmapMode == emu::MipmapMode::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST
                                                                    : VK_SAMPLER_MIPMAP_MODE_LINEAR;
          si.addressModeU = si.addressModeV = si.addressModeW = vkAddress(am);
          si.mipLodBias = sd.lodBias;
          si.minLod = sd.minLod;
          si.maxLod = sd.maxLod;
          vk::Sampler sampler(ctx, si);
          for (emu::Stage stage : {emu::Stage::Compute, emu::Stage::Fragment}) {
            const char* stageName = stage == emu::Stage::Compute ? "compute" : "fragment";
            if (opts.implicitLod && (stage == emu::Stage::Compute || fi < 0)) continue;  // texture() needs quads
            if (!opts.stages.empty() &&
                ("," + opts.stages + ",").find(std::string(",") + stageName + ",") == std::string::npos)
              continue;
            for (size_t i = 0; i < n; ++i) {
              if (fi < 0) {
                uint32_t lvl = rng() % tex.levelCount();
                int32_t v[4] = {int32_t(rng() % tex.levelWidth(lvl)), int32_t(rng() % tex.levelHeight(lvl)),
                                int32_t(rng() % tex.layers()), int32_t(lvl)};
                std::memcpy(&q[4 * i], v, 16);
              } else if (!opts.implicitLod) {
                q[4 * i] = randomCoord(rng, tex.width());
                q[4 * i + 1] = randomCoord(rng, tex.height());
                q[4 * i + 2] = float(rng() % tex.layers());
                q[4 * i + 3] = randomLod(rng, tex.levelCount());
              }
            }
            if (opts.implicitLod) smoothQueries(rng, tex, q, n);
            {
              if (fi < 0) {
                for (size_t i = 0; i < n; ++i) {
                  int32_t v[4];
                  std::memcpy(v, &q[4 * i], 16);
                  emu::Texel4 t = emu::texelFetch(tex, v[0], v[1], v[2], v[3]);
                  std::memcpy(&emuOut[4 * i], &t, 16);
                }
              } else {
                if (stage == emu::Stage::Compute) {
                  emu::textureLodBatch(tex, sd, profile, stage, q.data(), emuOut.data(), n, computeVectors.data());
                } else {
                  qFrag.assign(q.begin(), q.end());
                  qFrag.resize(4 * fragLanes.size(), 0.0f);  // masked lanes load zeros
                  if (opts.implicitLod) implicitLods(tex, sd, profile, q, primitiveOf, fragLanes, qFrag, n);
                  outFrag.resize(qFrag.size());
                  emu::textureLodBatch(tex, sd, profile, stage, qFrag.data(), outFrag.data(), fragLanes.size(),
                                       fragVectors.data());
                  std::copy(outFrag.begin(), outFrag.begin() + 4 * n, emuOut.begin());
                }
              }
            }
            std::memcpy(qBuf.data(), q.data(), n * 16);
            struct {
              uint32_t mode, count, width;
            } push{fi < 0 ? 1u : opts.implicitLod ? 2u : 0u, uint32_t(n), 1024};
            const vk::Binding binds[] = {{layout[0], VK_NULL_HANDLE, image.view(), sampler.handle()},
                                         {layout[1], qBuf.handle()},
                                         {layout[2], rBuf.handle()}};
            (stage == emu::Stage::Compute ? comp : frag).run(binds, &push, uint32_t(n), 1024);
            std::memcpy(gpu.data(), rBuf.data(), n * 16);
            uint64_t same = 0;
            int64_t maxUlp = 0;
            size_t firstBad = n;
            for (size_t i = 0; i < n; ++i) {
              bool ok = true;
              for (int c = 0; c < 4; ++c) {
                ok = ok && sameBits(emuOut[4 * i + c], gpu[4 * i + c]);
                maxUlp = std::max(maxUlp, ulpDistance(emuOut[4 * i + c], gpu[4 * i + c]));
              }
              same += ok;
              if (!ok && firstBad == n) firstBad = i;
            }
            identical += same;
            total += n;
            if (opts.seeds > 1 && same == n) continue;
            if (opts.seeds > 1) out << "seed " << seed << ": ";
            out << std::left << std::setw(8) << emu::formatInfo(fmt).name << std::setw(16)
                << (fi < 0 ? "texelFetch" : kFilters[fi].name) << std::setw(8) << emu::addressName(am) << std::setw(10)
                << (stage == emu::Stage::Compute ? "compute" : "fragment") << std::right << std::setw(10) << same << "/"
                << std::left << std::setw(11) << n << std::right << std::setw(10) << maxUlp;
            if (firstBad < n) {
              size_t i = firstBad;
              out << "   first diff #" << i << " (x " << i % 1024 << ", y " << i / 1024 << "): tex " << tex.width()
                  << "x" << tex.height() << "x" << tex.layers() << " L" << tex.levelCount() << " bias " << sd.lodBias
                  << " lod[" << sd.minLod << "," << sd.maxLod << "] q=(" << std::setprecision(9) << q[4 * i] << ", "
                  << q[4 * i + 1] << ", " << q[4 * i + 2] << ", " << q[4 * i + 3] << ") emu=(" << emuOut[4 * i] << ", "
                  << emuOut[4 * i + 1] << ") gpu=(" << gpu[4 * i] << ", " << gpu[4 * i + 1] << ")"
                  << std::setprecision(6);
              if (opts.implicitLod) {
                size_t x = i % 1024 & ~size_t(1), y = i / 1024 & ~size_t(1);
                size_t p[4] = {y * 1024 + x, y * 1024 + x + 1, (y + 1) * 1024 + x, (y + 1) * 1024 + x + 1};
                out << std::setprecision(9) << " quad:";
                for (int c = 0; c < 4; ++c) out << " (" << q[4 * p[c]] << "," << q[4 * p[c] + 1] << ")";
                for (size_t k = 0; k < fragLanes.size(); ++k) if (fragLanes[k].pixel == i) out << " lod " << qFrag[4 * k + 3];
                out << std::setprecision(6);
              }
            }
            out << "\n";
          }
        }
      }
    }
    if (opts.seeds > 1)
      out << "seed " << seed << ": " << identical - seedIdentical << "/" << total - seedTotal << " bit-identical\n";
  }
  if (ctx.validationEnabled())
    out << "validation errors: " << ctx.validationErrors()
        << (ctx.validationErrors() ? " (" + ctx.lastValidationMessage + ")" : "") << "\n";
  UlpTally all{"lookups (every format x filter x address mode x stage)"};
  all.identical = identical, all.total = total;
  writeVerifyReports(opts, {"texture", ctx.deviceName(), opts.image, 0, {all}, ctx.validationErrors(), ctx.lastValidationMessage}, out);
  out << "texture: " << identical << "/" << total << " bit-identical\n";
  return (identical == total && ctx.validationErrors() == 0) ? 0 : 1;
}

}  // namespace shadetwin
