// Emulated texture unit: format decoding, texture validation, sampler model spot checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "emu/device_profile.h"
#include "emu/format.h"
#include "emu/sampler.h"
#include "emu/texture.h"
#include "lanes/instantiate.h"

namespace {
std::vector<uint8_t> floats(std::initializer_list<float> v) {
  std::vector<uint8_t> b(v.size() * 4);
  std::memcpy(b.data(), v.begin(), b.size());
  return b;
}
}  // namespace

TEST(Format, HalfRoundTripsExhaustively) {
  for (uint32_t h = 0; h < 65536; ++h) {
    float f = emu::halfToFloat(uint16_t(h));
    if (std::isnan(f)) continue;
    ASSERT_EQ(emu::floatToHalf(f), h) << std::hex << h;
  }
  EXPECT_EQ(emu::halfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(emu::halfToFloat(0x7bff), 65504.0f);
}

TEST(Format, UnknownFormatNamesTheValue) {
  try {
    emu::parseFormat("rgb565");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rgb565"), std::string::npos);
  }
  EXPECT_EQ(emu::parseFormat("RGBA16F"), emu::Format::RGBA16F);
}

TEST(Texture, RejectsBadShapesWithClearErrors) {
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 0, 4, 1, {{}}), std::invalid_argument);
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 4, 4, 1, {}), std::invalid_argument);
  std::vector<std::vector<uint8_t>> tooMany(4, std::vector<uint8_t>(4));
  EXPECT_THROW(emu::Texture(emu::Format::R32F, 2, 2, 1, tooMany), std::invalid_argument);
  try {
    emu::Texture(emu::Format::RGBA8_UNORM, 4, 4, 1, {std::vector<uint8_t>(64), std::vector<uint8_t>(15)});
    FAIL();
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("level 1 has 15 bytes, expected 16"), std::string::npos) << m;
  }
}

TEST(Sampler, BilinearAtTexelCentresReturnsTexels) {
  emu::Texture t(emu::Format::R32F, 2, 1, 1, {floats({1.0f, 3.0f})});
  emu::SamplerDesc s;
  s.minFilter = s.magFilter = emu::Filter::Linear;
  const auto& lp = emu::lavapipeProfile();
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.25f, 0.5f, 0, 0).r, 1.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.75f, 0.5f, 0, 0).r, 3.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0).r, 2.0f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0).a, 1.0f);  // R32F alpha
  s.addressU = emu::AddressMode::Repeat;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.0f, 0.5f, 0, 0).r, 2.0f);  // wraps between texel 1 and 0
}

TEST(Sampler, ImplicitLodFastLog2) {
  // A 64 x 32 texture; quads (TL, TR, BL, BR) whose coordinates step k texels per pixel in x.
  emu::Texture t(emu::Format::R32F, 64, 32, 1, {std::vector<uint8_t>(64 * 32 * 4)});
  auto quad = [&](float kx, float ky, const emu::DeviceProfile& dev) {
    const float s[4] = {0.25f, 0.25f + kx / 64.0f, 0.25f, 0.25f + kx / 64.0f};
    const float tt[4] = {0.5f, 0.5f, 0.5f + ky / 32.0f, 0.5f + ky / 32.0f};
    emu::SamplerDesc sd;  // mip linear: the float LOD
    return emu::implicitLod(t, sd, dev, s, tt);
  };
  const auto& lp = emu::lavapipeProfile();
  // rho^2 = 1, 4, 16: powers of two are exact: lod 0, 1, 2.
  EXPECT_EQ(quad(1, 1, lp), 0.0f);
  EXPECT_EQ(quad(2, 1, lp), 1.0f);
  EXPECT_EQ(quad(1, 4, lp), 2.0f);
  // Between them the log2 is linear in the mantissa: rho^2 = 9 (3 texels/pixel) gives
  // ((3 - 1) + 1.125) / 2 = 1.5625, not log2(3) = 1.585 (the profile's "fast log2").
  EXPECT_EQ(quad(3, 1, lp), 1.5625f);
  EXPECT_NEAR(quad(3, 1, emu::nvidiaProfile()), std::log2(3.0), 1e-6);
  // Magnification: half a texel per pixel -> -1; no change at all -> the log2 of 0 (-127 / 2).
  EXPECT_EQ(quad(0.5f, 0.5f, lp), -1.0f);
  EXPECT_EQ(quad(0, 0, lp), -63.5f);
}

TEST(Sampler, DialectTextureUsesTheQuadLod) {
  // shade::x8 texture(): two quads; the first steps 2 texels per pixel (LOD 1), the second 1/2 (LOD -1,
  // magnified): texture() must equal textureLod at those LODs, lane for lane.
  std::vector<std::vector<uint8_t>> levels;
  for (uint32_t w = 64, h = 32; ; w = std::max(1u, w / 2), h = std::max(1u, h / 2)) {
    std::vector<float> v(size_t(w) * h * 4);
    for (size_t i = 0; i < v.size(); ++i) v[i] = float((i * 2654435761u) % 1000) / 1000.0f;
    levels.push_back(std::vector<uint8_t>(v.size() * 4));
    std::memcpy(levels.back().data(), v.data(), v.size() * 4);
    if (w == 1 && h == 1) break;
  }
  emu::Texture t(emu::Format::RGBA32F, 64, 32, 1, levels);
  shadetwin::shade::Sampler2D s{&t, {}, &emu::lavapipeProfile()};
  using F = emu::F32<8>;
  F u, v, lod;
  const float step[2] = {2.0f / 64.0f, 0.5f / 64.0f}, lodOf[2] = {1.0f, -1.0f};
  for (int q = 0; q < 2; ++q)
    for (int i = 0; i < 4; ++i) {
      u.set(4 * q + i, 0.3f + step[q] * float(i & 1) + 0.01f * float(q));
      v.set(4 * q + i, 0.6f + step[q] * 2.0f * float(i >> 1));  // 64 x 32: same texel step in v
      lod.set(4 * q + i, lodOf[q]);
    }
  auto a = shadetwin::shade::x8::texture(s, shadetwin::shade::V2<F>(u, v));
  auto b = shadetwin::shade::x8::textureLod(s, shadetwin::shade::V2<F>(u, v), lod);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(a.x[i], b.x[i]) << i;
    EXPECT_EQ(a.w[i], b.w[i]) << i;
  }
}

TEST(Sampler, Unorm8FixedPointPathMatchesLavapipeFacts) {
  // 2x1 RGBA8 texture (0, 255); u = 0.3 -> s = rint(0.6 * 256) - 128 = 26, w = 26:
  // 0 + ((26 * 255 + 128) >> 8) = 26 -> 26 * (1/255f).
  std::vector<uint8_t> px = {0, 0, 0, 0, 255, 255, 255, 255};
  emu::Texture t(emu::Format::RGBA8_UNORM, 2, 1, 1, {px});
  emu::SamplerDesc s;
  emu::Texel4 r = emu::textureLod(t, s, emu::lavapipeProfile(), 0.3f, 0.5f, 0, 0);
  EXPECT_EQ(r.r, 26.0f * (1.0f / 255.0f));
  // The float path (nvidia profile, 8-bit weights) filters the same lookup differently.
  emu::Texel4 n = emu::textureLod(t, s, emu::nvidiaProfile(), 0.3f, 0.5f, 0, 0);
  EXPECT_NE(n.r, r.r);
}

TEST(Sampler, FilterLerpIsFusedOrAMultiplyThenAnAdd) {
  // DeviceProfile::filterLerpFma: lavapipe fma(w, b - a, a); SwiftShader a + w (b - a), rounded twice.
  // A 2x1 R32F texture and many u: both forms are reproduced exactly, and they differ for some u.
  const float a = 0.1f, b = 0.7f;
  emu::Texture t(emu::Format::R32F, 2, 1, 1, {floats({a, b})});
  emu::SamplerDesc s;  // linear, clamp
  int differ = 0;
  for (int k = 1; k < 200; ++k) {
    const float u = 0.25f + 0.5f * float(k) / 200.0f;  // between the texel centres: w = 2u - 0.5
    const float w = u * 2.0f - 0.5f;
    const float fused = std::fma(w, b - a, a);
    const float p = w * (b - a), split = a + p;
    EXPECT_EQ(emu::textureLod(t, s, emu::lavapipeProfile(), u, 0.5f, 0, 0).r, fused) << u;
    EXPECT_EQ(emu::textureLod(t, s, emu::swiftshaderProfile(), u, 0.5f, 0, 0).r, split) << u;
    differ += fused != split;
  }
  EXPECT_GT(differ, 10);
}

TEST(Sampler, TrilinearBlendsLevelsWithFma) {
  emu::Texture t(emu::Format::R32F, 2, 2, 1, {floats({1, 1, 1, 1}), floats({3})});
  emu::SamplerDesc s;
  const auto& lp = emu::lavapipeProfile();
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 1.5f);
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 5.0f).r, 3.0f);   // clamped to the last level
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, -3.0f).r, 1.0f);  // magnified
  s.lodBias = 0.5f;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 2.5f);
  s.maxLod = 0.5f;
  EXPECT_EQ(emu::textureLod(t, s, lp, 0.5f, 0.5f, 0, 0.25f).r, 2.0f);
}

TEST(Sampler, SwiftShaderAlwaysBlendsLevelsAndAnInfTexelThenGivesNaN) {
  // MipSelection::Reactor: linear mip blends (cc - c) frac + c even at fraction 0, so an inf texel of level 0
  // gives NaN at lod 0 (inf - inf); lavapipe does not lerp at fraction 0 and returns inf (verify texture,
  // the one-level-of-inf textures).
  emu::Texture t(emu::Format::R32F, 2, 2, 1, {floats({INFINITY, INFINITY, INFINITY, INFINITY}), floats({3})});
  emu::SamplerDesc s;
  s.magFilter = s.minFilter = emu::Filter::Nearest;  // no bilinear arithmetic (inf - inf) inside the level
  EXPECT_EQ(emu::textureLod(t, s, emu::lavapipeProfile(), 0.5f, 0.5f, 0, 0.0f).r, INFINITY);
  EXPECT_TRUE(std::isnan(emu::textureLod(t, s, emu::swiftshaderProfile(), 0.5f, 0.5f, 0, 0.0f).r));
  s.magFilter = s.minFilter = emu::Filter::Linear;
  // Both clamp lod above the last level; SwiftShader's clamp is 13 (its sampler LOD limit), lavapipe's the level.
  emu::Texture f(emu::Format::R32F, 2, 2, 1, {floats({1, 1, 1, 1}), floats({3})});
  EXPECT_EQ(emu::textureLod(f, s, emu::swiftshaderProfile(), 0.5f, 0.5f, 0, 0.25f).r, 1.5f);
  EXPECT_EQ(emu::textureLod(f, s, emu::swiftshaderProfile(), 0.5f, 0.5f, 0, 20.0f).r, 3.0f);
}

TEST(Sampler, SwiftShaderRgba8PointFilterIs16BitFixedPoint) {
  // Unorm8Path::Reactor, FILTER_POINT: u in 0.16 fixed point, texel index (u16 * W) >> 16. v = 1/7 on a
  // 1x7 texture is row 1 in float (1/7 * 7 = 1) but row 0 in 0.16 fixed point (9362 * 7 >> 16 = 0), the
  // case verify texture found; and the mip blend of a one-texel chain loses one 16-bit unit: 255 << 8 = 65280,
  // * 0x7FFF >> 16 + * 0x8000 >> 16 = 32639 + 32640 = 65279 -> 65279 / 65280.
  std::vector<uint8_t> rows(7 * 4);
  for (int y = 0; y < 7; ++y) rows[size_t(4 * y)] = uint8_t(10 * y);
  emu::Texture t(emu::Format::RGBA8_UNORM, 1, 7, 1, {rows});
  emu::SamplerDesc s;
  s.magFilter = s.minFilter = emu::Filter::Nearest, s.mipmapMode = emu::MipmapMode::Nearest;
  const float v = 0.142857149f;
  EXPECT_EQ(emu::textureLod(t, s, emu::lavapipeProfile(), 0.5f, v, 0, 0).r, emu::unorm8ToFloat(10));
  EXPECT_EQ(emu::textureLod(t, s, emu::swiftshaderProfile(), 0.5f, v, 0, 0).r, 0.0f);
  std::vector<uint8_t> white = {255, 255, 255, 255}, white2 = {255, 255, 255, 255, 255, 255, 255, 255};
  emu::Texture chain(emu::Format::RGBA8_UNORM, 2, 1, 1, {white2, white});
  s.mipmapMode = emu::MipmapMode::Linear;
  EXPECT_EQ(emu::textureLod(chain, s, emu::swiftshaderProfile(), 0.25f, 0.5f, 0, 0.5f).r, 65279.0f * (1.0f / 65280.0f));
  EXPECT_EQ(emu::textureLod(chain, s, emu::lavapipeProfile(), 0.25f, 0.5f, 0, 0.5f).r, 1.0f);
}

TEST(Sampler, SwiftShaderImplicitLodReadsTheBitsOfRho4) {
  // ImplicitLod::ReactorLog2Sqrt: exact at powers of two (rho^2 = 2^m: lod = m / 2), piecewise linear between,
  // so it differs from log2 inside an octave and from lavapipe's fast log2 (which reads rho^2's mantissa).
  emu::Texture t(emu::Format::R32F, 64, 64, 1, {std::vector<uint8_t>(64 * 64 * 4)});
  emu::SamplerDesc s;
  const float su[4] = {0, 4.0f / 64, 0, 4.0f / 64}, tv[4] = {0, 0, 4.0f / 64, 4.0f / 64};  // rho = 4
  EXPECT_EQ(emu::implicitLod(t, s, emu::swiftshaderProfile(), su, tv), 2.0f);
  const float su3[4] = {0, 3.0f / 64, 0, 3.0f / 64}, tv3[4] = {0, 0, 3.0f / 64, 3.0f / 64};  // rho = 3, rho^4 = 81
  const float ss = emu::implicitLod(t, s, emu::swiftshaderProfile(), su3, tv3);
  EXPECT_EQ(ss, (float(0x42A20000) - float(0x3F800000)) * 0x1p-25f);  // bits of 81.0f
  EXPECT_NE(ss, emu::implicitLod(t, s, emu::lavapipeProfile(), su3, tv3));
  EXPECT_NEAR(ss, std::log2(3.0f), 0.1f);
}

TEST(DeviceProfile, LookupAndUnknownNames) {
  EXPECT_TRUE(emu::profileByName("lavapipe").verified);
  EXPECT_FALSE(emu::profileByName("nvidia").verified);
  EXPECT_EQ(emu::profileForDevice("llvmpipe (LLVM 15.0.6, 256 bits)").name, "lavapipe");
  // SwiftShader (issue 18): found by its device name; verified (every verify suite bit-identical).
  EXPECT_EQ(emu::profileForDevice("SwiftShader Device (Subzero)").name, "swiftshader");
  EXPECT_TRUE(emu::profileByName("swiftshader").verified);
  EXPECT_EQ(emu::swiftshaderProfile().raster.subPixelBits, 4);  // limits.subPixelPrecisionBits
  EXPECT_FALSE(emu::swiftshaderProfile().raster.fineDerivatives);
  EXPECT_EQ(emu::profileByName("swiftshader").loopIterationLimit, 0u);
  EXPECT_EQ(emu::swiftshaderProfile().denorm(emu::Stage::Compute), emu::DenormMode::Flush);  // verify math, measured
  EXPECT_FALSE(emu::swiftshaderProfile().filterLerpFma);  // verify texture, measured
  EXPECT_EQ(emu::swiftshaderProfile().texAddressing, emu::DeviceProfile::TexAddressing::Reactor);
  EXPECT_EQ(emu::lavapipeProfile().mipSelection, emu::DeviceProfile::MipSelection::Gallivm);
  EXPECT_TRUE(emu::lavapipeProfile().filterLerpFma);
  EXPECT_THROW(emu::profileByName("voodoo2"), std::invalid_argument);
  EXPECT_EQ(emu::lavapipeProfile().denorm(emu::Stage::Fragment), emu::DenormMode::Flush);
  EXPECT_EQ(emu::lavapipeProfile().denorm(emu::Stage::Compute), emu::DenormMode::Preserve);
}

TEST(DeviceProfile, FieldsCanBeSetToTheirAlternatives) {
  emu::DeviceProfile p = emu::lavapipeProfile();
  emu::setProfileField(p, "maskedFragmentLanes=skip");
  EXPECT_EQ(p.maskedFragmentLanes, emu::DeviceProfile::MaskedFragmentLanes::Skip);
  EXPECT_FALSE(p.verified);  // an alternative is not what was measured
  EXPECT_NE(p.name.find("maskedFragmentLanes=skip"), std::string::npos);
  emu::setProfileField(p, "implicitNearestShortcut", "false");
  EXPECT_FALSE(p.implicitNearestShortcut);
  emu::setProfileField(p, "computeVectorLanes=4");
  EXPECT_EQ(p.computeVectorLanes, 4);
  emu::setProfileField(p, "denormFragment=preserve");
  EXPECT_EQ(p.denormFragment, emu::DenormMode::Preserve);
  auto message = [&](const char* kv) {
    try {
      emu::setProfileField(p, kv);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("voodoo=1").find("unknown profile field 'voodoo'"), std::string::npos);
  EXPECT_NE(message("computeVectorLanes=0").find("expected an integer in [1, 64]"), std::string::npos);
  EXPECT_NE(message("computeVectorLanes=8x").find("got '8x'"), std::string::npos);
  EXPECT_NE(message("implicitNearestShortcut").find("expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(message("maskedFragmentLanes=maybe").find("expected sample or skip"), std::string::npos);
  EXPECT_EQ(emu::lavapipeProfile().maskedFragmentLanes, emu::DeviceProfile::MaskedFragmentLanes::Sample);
}

TEST(Sampler, ImplicitNearestShortcutTakesTheLevelFromTheExponent) {
  // gallivm's lp_build_ilog2_sqrt: with mip nearest and nothing after the log2, level =
  // (exponent(rho^2) + 1) >> 1; the float path rounds 0.5 fastlog2(rho^2) to even. A 64 x 64 texture
  // and quads stepping a texels in s and b texels in t per pixel in x: rho^2 = a^2 + b^2.
  emu::Texture t(emu::Format::R32F, 64, 64, 1, {std::vector<uint8_t>(64 * 64 * 4)});
  auto lod = [&](float a, float b, const emu::SamplerDesc& sd, const emu::DeviceProfile& dev) {
    const float s[4] = {0.25f, 0.25f + a / 64.0f, 0.25f, 0.25f + a / 64.0f};
    const float tt[4] = {0.5f, 0.5f + b / 64.0f, 0.5f, 0.5f + b / 64.0f};
    return emu::implicitLod(t, sd, dev, s, tt);
  };
  const auto& lp = emu::lavapipeProfile();
  emu::DeviceProfile alt = lp;
  emu::setProfileField(alt, "implicitNearestShortcut=false");
  emu::SamplerDesc nearest;
  nearest.mipmapMode = emu::MipmapMode::Nearest;
  // Ties of the float LOD, rho^2 = 2^(2k+1): rint(k + 1/2) goes to even, the shortcut up.
  EXPECT_EQ(lod(1, 1, nearest, lp), 1.0f);     // rho^2 = 2: LOD 0.5, shortcut level 1
  EXPECT_EQ(lod(1, 1, nearest, alt), 0.5f);    // the float path: rint -> level 0
  EXPECT_EQ(lod(4, 4, nearest, lp), 3.0f);     // rho^2 = 32: LOD 2.5 -> shortcut 3, rint 2
  EXPECT_EQ(lod(4, 4, nearest, alt), 2.5f);
  EXPECT_EQ(lod(2, 2, nearest, lp), 2.0f);     // rho^2 = 8: LOD 1.5 -> both 2
  EXPECT_EQ(lod(0.25f, 0.25f, nearest, lp), -1.0f);  // rho^2 = 1/8: LOD -1.5 -> shortcut -1
  // Level 0: minified (rho^2 > 1) or not, as the min/mag choice of the shortcut.
  EXPECT_EQ(lod(1.2f, 0, nearest, lp), 0.25f);
  EXPECT_EQ(lod(1, 0, nearest, lp), 0.0f);
  EXPECT_EQ(lod(0.8f, 0, nearest, lp), 0.0f);
  // Anything after the log2 (bias, minLod > 0, maxLod < 15) or mip linear: the float LOD.
  emu::SamplerDesc biased = nearest, minClamped = nearest, maxClamped = nearest, linear;
  biased.lodBias = 0.75f;
  minClamped.minLod = 0.5f;
  maxClamped.maxLod = 14.0f;
  for (const auto* sd : {&biased, &minClamped, &maxClamped, &linear}) EXPECT_EQ(lod(1, 1, *sd, lp), 0.5f);
  maxClamped.maxLod = 15.0f;
  EXPECT_EQ(lod(1, 1, maxClamped, lp), 1.0f);
  // Through the sampler: the level texture() reads.
  std::vector<std::vector<uint8_t>> levels;
  for (uint32_t l = 0; l < 7; ++l) {
    const uint32_t w = 64u >> l;
    std::vector<float> v(size_t(w) * w, float(l));
    levels.emplace_back(v.size() * 4);
    std::memcpy(levels.back().data(), v.data(), levels.back().size());
  }
  emu::Texture chain(emu::Format::R32F, 64, 64, 1, levels);
  nearest.minFilter = nearest.magFilter = emu::Filter::Nearest;
  EXPECT_EQ(emu::textureLod(chain, nearest, lp, 0.3f, 0.3f, 0, lod(4, 4, nearest, lp)).r, 3.0f);
  EXPECT_EQ(emu::textureLod(chain, nearest, alt, 0.3f, 0.3f, 0, lod(4, 4, nearest, alt)).r, 2.0f);
}

// ---- batch path (8 lanes + TBB) against the one-lane model ----
#include <tbb/global_control.h>

#include <random>

namespace {
emu::Texture randomFloatTexture(emu::Format fmt, uint32_t w, uint32_t h, std::mt19937& rng) {
  std::vector<std::vector<uint8_t>> levels;
  const uint32_t tb = emu::formatInfo(fmt).texelBytes;
  for (uint32_t l = 0; l < emu::Texture::fullChainLevels(w, h); ++l) {
    uint32_t lw = std::max(1u, w >> l), lh = std::max(1u, h >> l);
    std::vector<uint8_t> b(size_t(lw) * lh * tb);
    for (size_t i = 0; i < b.size(); i += 4) {
      float v = std::uniform_real_distribution<float>(-3.0f, 3.0f)(rng);
      if (fmt == emu::Format::RGBA16F) {
        uint16_t h0 = emu::floatToHalf(v), h1 = emu::floatToHalf(-v);
        std::memcpy(&b[i], &h0, 2);
        std::memcpy(&b[i + 2], &h1, 2);
      } else if (fmt == emu::Format::RGBA8_UNORM) {
        for (int c = 0; c < 4; ++c) b[i + c] = uint8_t(rng());
      } else {
        std::memcpy(&b[i], &v, 4);
      }
    }
    levels.push_back(std::move(b));
  }
  return emu::Texture(fmt, w, h, 1, std::move(levels));
}
}  // namespace

TEST(SamplerBatch, EightLanePathEqualsOneLaneModelEverywhere) {
  std::mt19937 rng(17);
  const size_t n = 1003;  // a tail shorter than 8 lanes
  std::vector<float> q(4 * n), out(4 * n);
  for (emu::Format fmt : emu::kAllFormats)
    for (auto mode : {emu::AddressMode::ClampToEdge, emu::AddressMode::Repeat, emu::AddressMode::MirroredRepeat})
      for (int f = 0; f < 4; ++f) {
        emu::Texture tex = randomFloatTexture(fmt, 13 + f, 8, rng);
        emu::SamplerDesc s;
        s.addressU = s.addressV = mode;
        s.minFilter = (f & 1) ? emu::Filter::Linear : emu::Filter::Nearest;
        s.magFilter = f == 3 ? emu::Filter::Nearest : s.minFilter;  // f == 3: mixed
        s.mipmapMode = (f & 2) ? emu::MipmapMode::Linear : emu::MipmapMode::Nearest;
        for (size_t i = 0; i < n; ++i) {
          q[4 * i] = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
          q[4 * i + 1] = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
          q[4 * i + 2] = 0.0f;
          q[4 * i + 3] = (i % 5 == 0) ? float(i % 4) : std::uniform_real_distribution<float>(-1.0f, 5.0f)(rng);
        }
        for (const emu::DeviceProfile* dev : {&emu::lavapipeProfile(), &emu::nvidiaProfile()}) {
          emu::textureLodBatch(tex, s, *dev, emu::Stage::Compute, q.data(), out.data(), n);
          for (size_t i = 0; i < n; ++i) {
            emu::Texel4 t = emu::textureLod(tex, s, *dev, q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
            ASSERT_EQ(0, std::memcmp(&t, &out[4 * i], 16))
                << emu::formatInfo(fmt).name << " " << emu::addressName(mode) << " case " << f << " query " << i;
          }
        }
      }
}

TEST(SamplerBatch, ResultsDoNotDependOnThreadCount) {
  std::mt19937 rng(23);
  emu::Texture tex = randomFloatTexture(emu::Format::RGBA32F, 64, 64, rng);
  const size_t n = 50000;
  std::vector<float> q(4 * n);
  for (auto& v : q) v = std::uniform_real_distribution<float>(-1.0f, 6.0f)(rng);
  std::vector<uint32_t> vec(n);
  for (size_t i = 0; i < n; ++i) vec[i] = uint32_t(i / 8);
  emu::SamplerDesc s;
  std::vector<std::vector<float>> outs;
  for (int threads : {1, 2, 16}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    outs.emplace_back(4 * n);
    emu::textureLodBatch(tex, s, emu::lavapipeProfile(), emu::Stage::Fragment, q.data(), outs.back().data(), n, vec.data());
  }
  EXPECT_EQ(0, std::memcmp(outs[0].data(), outs[1].data(), 16 * n));
  EXPECT_EQ(0, std::memcmp(outs[0].data(), outs[2].data(), 16 * n));
}

TEST(SamplerBatch, LanesOfOneVectorShareTheLerpDecision) {
  // The probe experiment: level 1 is +inf, one lane at lod 0.5, the rest at lod 0. Lanes in the
  // probe's vector lerp with fraction 0 -> fma(0, inf - 1, 1) = NaN; other vectors return 1.
  emu::Texture tex(emu::Format::R32F, 2, 2, 1, {floats({1, 1, 1, 1}), floats({INFINITY})});
  emu::SamplerDesc s;
  s.minFilter = s.magFilter = emu::Filter::Nearest;
  const size_t n = 16;
  std::vector<float> q(4 * n, 0.25f), out(4 * n);
  for (size_t i = 0; i < n; ++i) q[4 * i + 3] = i == 3 ? 0.5f : 0.0f;
  std::vector<uint32_t> vec(n);
  for (size_t i = 0; i < n; ++i) vec[i] = uint32_t(i / 8);
  emu::textureLodBatch(tex, s, emu::lavapipeProfile(), emu::Stage::Compute, q.data(), out.data(), n, vec.data());
  EXPECT_TRUE(std::isinf(out[4 * 3]));
  for (size_t i = 0; i < 8; ++i) {
    if (i != 3) {
      EXPECT_TRUE(std::isnan(out[4 * i])) << i;
    }
  }
  for (size_t i = 8; i < 16; ++i) EXPECT_EQ(out[4 * i], 1.0f) << i;
  emu::textureLodBatch(tex, s, emu::lavapipeProfile(), emu::Stage::Compute, q.data(), out.data(), n, nullptr);
  EXPECT_EQ(out[0], 1.0f);  // per-lane decisions: no lerp at fraction 0
}
