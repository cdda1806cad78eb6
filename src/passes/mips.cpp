#include "passes/mips.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "lanes/instantiate.h"
#include "model/counted.h"
#include "vk/context.h"

namespace shadetwin {

namespace {
#include "mip_downsample.inc"

void checkShape(const std::vector<float>& level0, uint32_t w, uint32_t h, uint32_t layers) {
  if (w == 0 || h == 0 || layers == 0) throw std::invalid_argument("mip chain: zero-sized texture");
  if (level0.size() != size_t(w) * h * layers * 4)
    throw std::invalid_argument("mip chain: level 0 has " + std::to_string(level0.size()) + " floats, expected " +
                                std::to_string(size_t(w) * h * layers * 4));
}

// One destination level through the scalar build.
void downsampleScalar(const float* src, float* dst, int sw, int sh, int layers) {
  namespace S = shade::scalar;
  const int dw = std::max(1, sw >> 1), dh = std::max(1, sh >> 1);
  auto at = [&](int layer, int x, int y) {
    const float* p = src + 4 * ((size_t(layer) * sh + std::min(y, sh - 1)) * sw + std::min(x, sw - 1));
    return shade::V4<float>(p[0], p[1], p[2], p[3]);
  };
  for (int layer = 0; layer < layers; ++layer)
    for (int y = 0; y < dh; ++y) {
      S::MipTaps ty = S::mipTaps(y, sh);
      for (int x = 0; x < dw; ++x) {
        S::MipTaps tx = S::mipTaps(x, sw);
        shade::V4<float> r[3];
        for (int k = 0; k < 3; ++k)
          r[k] = S::mipCombine(at(layer, tx.i0, ty.i0 + k), at(layer, tx.i0 + 1, ty.i0 + k), at(layer, tx.i0 + 2, ty.i0 + k), tx);
        shade::V4<float> v = S::mipCombine(r[0], r[1], r[2], ty);
        float* o = dst + 4 * ((size_t(layer) * dh + y) * dw + x);
        o[0] = v.x; o[1] = v.y; o[2] = v.z; o[3] = v.w;
      }
    }
}

// The 8-lane driver over either lane build (an instantiation namespace): the SIMD build (the emulator) or the
// counting one (the model).
#define MIP_LANES(Name, NS)                                                                 \
  struct Name {                                                                             \
    using Float = shade::NS::Float;                                                         \
    using Int = shade::NS::Int;                                                             \
    using MipTaps = shade::NS::MipTaps;                                                     \
    static auto mipTaps(auto&&... a) { return shade::NS::mipTaps(a...); }                   \
    static auto mipCombine(auto&&... a) { return shade::NS::mipCombine(a...); }             \
  };
MIP_LANES(X8Lanes, x8)
MIP_LANES(CountedLanes, counted)
#undef MIP_LANES

// One destination level through the 8-lane SIMD build: 8 destination texels of a row per step.
template <class X>
void downsampleLanes(const float* src, float* dst, int sw, int sh, int layers) {
  using F = typename X::Float;
  using I = typename X::Int;
  using V4 = shade::V4<F>;
  const int dw = std::max(1, sw >> 1), dh = std::max(1, sh >> 1);
  auto gather = [&](int layer, I xs, int y) {
    V4 v(F(0.0f), F(0.0f), F(0.0f), F(0.0f));
    const int cy = std::min(y, sh - 1);
    for (int l = 0; l < 8; ++l) {
      const float* p = src + 4 * ((size_t(layer) * sh + cy) * sw + std::min(xs[l], sw - 1));
      v.x.set(l, p[0]); v.y.set(l, p[1]); v.z.set(l, p[2]); v.w.set(l, p[3]);
    }
    return v;
  };
  for (int layer = 0; layer < layers; ++layer)
    for (int y = 0; y < dh; ++y) {
      for (int x0 = 0; x0 < dw; x0 += 8) {
        I xs;
        for (int l = 0; l < 8; ++l) xs.set(l, std::min(x0 + l, dw - 1));
        typename X::MipTaps tx = X::mipTaps(xs, I(sw));
        // The row's taps per vector, as every invocation of mip_downsample.glsl computes both: the counted build (the
        // performance model's) then counts the divisions the GPU runs (hoisted out of the row, a wide level counted
        // about half of them; tests/mips_test.cpp)
        typename X::MipTaps ty = X::mipTaps(I(y), I(sh));
        V4 r[3];
        const int y0 = ty.i0[0];  // the row is uniform across the 8 lanes
        for (int k = 0; k < 3; ++k)
          r[k] = X::mipCombine(gather(layer, tx.i0, y0 + k), gather(layer, tx.i0 + 1, y0 + k), gather(layer, tx.i0 + 2, y0 + k), tx);
        V4 v = X::mipCombine(r[0], r[1], r[2], ty);
        for (int l = 0; l < 8 && x0 + l < dw; ++l) {
          float* o = dst + 4 * ((size_t(layer) * dh + y) * dw + x0 + l);
          o[0] = v.x[l]; o[1] = v.y[l]; o[2] = v.z[l]; o[3] = v.w[l];
        }
      }
    }
}

}  // namespace

std::vector<std::vector<float>> mipChainCpu(const std::vector<float>& level0, uint32_t w, uint32_t h, uint32_t layers,
                                            int lanes) {
  checkShape(level0, w, h, layers);
  if (lanes != 1 && lanes != 8 && lanes != 0) throw std::invalid_argument("mipChainCpu: lanes must be 1 or 8");
  std::vector<std::vector<float>> levels{level0};
  const uint32_t n = emu::Texture::fullChainLevels(w, h);
  for (uint32_t l = 1; l < n; ++l) {
    const int sw = int(std::max(1u, w >> (l - 1))), sh = int(std::max(1u, h >> (l - 1)));
    const int dw = std::max(1, sw >> 1), dh = std::max(1, sh >> 1);
    std::vector<float> next(size_t(dw) * dh * layers * 4);
    (lanes == 1 ? downsampleScalar : lanes == 8 ? downsampleLanes<X8Lanes> : downsampleLanes<CountedLanes>)(
        levels.back().data(), next.data(), sw, sh, int(layers));
    levels.push_back(std::move(next));
  }
  return levels;
}

std::vector<std::vector<float>> mipChainGpu(vk::Context& ctx, const std::vector<float>& level0, uint32_t w, uint32_t h,
                                            uint32_t layers) {
  checkShape(level0, w, h, layers);
  const VkDescriptorType layout[] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
  vk::Kernel k(ctx, vk::Stage::Compute, kSpv_mip_downsample, layout, 12);
  std::vector<std::vector<float>> levels{level0};
  const uint32_t n = emu::Texture::fullChainLevels(w, h);
  for (uint32_t l = 1; l < n; ++l) {
    const int sw = int(std::max(1u, w >> (l - 1))), sh = int(std::max(1u, h >> (l - 1)));
    const uint32_t count = uint32_t(std::max(1, sw >> 1) * std::max(1, sh >> 1)) * layers;
    vk::Buffer src(ctx, levels.back().size() * 4), dst(ctx, size_t(count) * 16);
    std::memcpy(src.data(), levels.back().data(), levels.back().size() * 4);
    struct { int32_t w, h, layers; } push{sw, sh, int32_t(layers)};
    const vk::Binding b[] = {{layout[0], src.handle()}, {layout[1], dst.handle()}};
    k.run(b, &push, count);
    levels.emplace_back(size_t(count) * 4);
    std::memcpy(levels.back().data(), dst.data(), size_t(count) * 16);
  }
  return levels;
}

emu::Texture packTexture(emu::Format format, uint32_t w, uint32_t h, uint32_t layers, const std::vector<std::vector<float>>& levels) {
  std::vector<std::vector<uint8_t>> bytes;
  const uint32_t tb = emu::formatInfo(format).texelBytes;
  for (const auto& lv : levels) {
    const size_t texels = lv.size() / 4;
    std::vector<uint8_t> b(texels * tb);
    for (size_t t = 0; t < texels; ++t) {
      const float* p = &lv[4 * t];
      uint8_t* o = &b[t * tb];
      switch (format) {
        case emu::Format::RGBA32F: std::memcpy(o, p, 16); break;
        case emu::Format::R32F: std::memcpy(o, p, 4); break;
        case emu::Format::RGBA32UI: throw std::invalid_argument("packLevels: rgba32ui is an integer format, not packed from floats");
        case emu::Format::RGBA16F:
          for (int c = 0; c < 4; ++c) {
            uint16_t hv = emu::floatToHalf(p[c]);
            std::memcpy(o + 2 * c, &hv, 2);
          }
          break;
        case emu::Format::RGBA8_UNORM:
          for (int c = 0; c < 4; ++c) {
            float x = std::isnan(p[c]) ? 0.0f : std::min(std::max(p[c], 0.0f), 1.0f);
            o[c] = uint8_t(std::nearbyint(x * 255.0f));
          }
          break;
      }
    }
    bytes.push_back(std::move(b));
  }
  return emu::Texture(format, w, h, layers, std::move(bytes));
}

}  // namespace shadetwin
