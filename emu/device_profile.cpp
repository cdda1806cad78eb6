#include "emu/device_profile.h"

#include <cctype>
#include <charconv>
#include <stdexcept>
#include <string>

namespace emu {

const DeviceProfile& lavapipeProfile() {
  static const DeviceProfile p{
      "lavapipe", true,
      "Mesa 22.3.6 llvmpipe (LLVM 15, 256-bit), measured with `shadetwin verify texture` and ../shared/facts/lavapipe.md",
      /*filterWeightFracBits=*/0, /*lodFractionBits=*/0, DeviceProfile::Unorm8Path::Fixed8,
      /*computeVectorLanes=*/8, /*fragmentVectorW=*/4, /*fragmentVectorH=*/2,
      // masked lanes sample: verify texture --implicit-lod (docs/DESIGN.md s3, issue 14)
      DeviceProfile::MaskedFragmentLanes::Sample, DenormMode::Preserve, DenormMode::Flush,
      // verified with `shadetwin verify raster` on the shipped scenes, scenes/clipped.json included
      // (triangles crossing every clip plane)
      {/*subPixelBits=*/8, /*viewportFma=*/true, /*interpFma=*/true, /*cwSwapsLast=*/true, /*fineDerivatives=*/true,
       DeviceProfile::Raster::Clip::DrawModule, /*clipFromNearer=*/true, /*clipViewportFma=*/false,
       /*fansClippedPolygons=*/true, /*verified=*/true},
      DeviceProfile::ImplicitLod::FastLog2PerQuad, /*implicitLodVerified=*/true,  // verify texture --implicit-lod
      /*implicitNearestShortcut=*/true,
      /*loopIterationLimit=*/65535};  // gallivm lp_bld_limits.h; the glints lighting table's partial sums past it
  return p;
}

const DeviceProfile& nvidiaProfile() {
  static const DeviceProfile p{
      "nvidia", false,
      "public documentation only (CUDA programming guide, texture fetching: 9-bit weights with 8 fraction bits); "
      "not yet measured on a GPU",
      /*filterWeightFracBits=*/8, /*lodFractionBits=*/8, DeviceProfile::Unorm8Path::Float,
      /*computeVectorLanes=*/1, /*fragmentVectorW=*/1, /*fragmentVectorH=*/1,
      DeviceProfile::MaskedFragmentLanes::Skip, DenormMode::Preserve, DenormMode::Preserve,
      {/*subPixelBits=*/8, /*viewportFma=*/true, /*interpFma=*/true, /*cwSwapsLast=*/true, /*fineDerivatives=*/true,
       DeviceProfile::Raster::Clip::GuardBand, /*clipFromNearer=*/false, /*clipViewportFma=*/true,
       /*fansClippedPolygons=*/false, /*verified=*/false},
      DeviceProfile::ImplicitLod::Exact, /*implicitLodVerified=*/false, /*implicitNearestShortcut=*/false,
      /*loopIterationLimit=*/0};
  return p;
}

const DeviceProfile& swiftshaderProfile() {
  // Issue 18: SwiftShader (Google's CPU Vulkan driver, from @sparticuz/chromium 147.0.0), verified: every verify suite on
  // every shipped scene and technique bit-identical (docs/RESULTS.md, "SwiftShader"). Its texture unit and rasterizer are
  // re-implemented from the semantics of google/swiftshader (SamplerCore, VertexRoutine, SetupRoutine, QuadRasterizer,
  // PixelRoutine) as named strategies; the rest is measured with the harness.
  static const DeviceProfile p = [] {
    DeviceProfile q = lavapipeProfile();
    q.name = "swiftshader", q.verified = true;
    q.provenance = "SwiftShader 147.0.0 (@sparticuz/chromium, Subzero), measured with every `shadetwin verify` suite "
                   "(docs/RESULTS.md, SwiftShader); texture unit and rasterizer from google/swiftshader's semantics";
    q.denormCompute = DenormMode::Flush;
    // verify texture --filters bilinear,trilinear --count 2000 --seed 3 on SwiftShader: 163920/196608 with the
    // separate multiply and add of SamplerCore's blends, 111799/196608 fused.
    q.filterLerpFma = false;
    // SwiftShader's SamplerCore (issue 18): its addressing, LOD-to-level rules and 16-bit RGBA8 path, every
    // explicit-LOD lane sampled alone (SpirvShaderSampling.cpp loops over the lanes), SIMD width 4 (2x2 quads).
    q.texAddressing = DeviceProfile::TexAddressing::Reactor;
    q.mipSelection = DeviceProfile::MipSelection::Reactor;
    q.unorm8Path = DeviceProfile::Unorm8Path::Reactor;
    q.computeVectorLanes = 4, q.fragmentVectorW = 2, q.fragmentVectorH = 2;
    q.raster.verified = true, q.implicitLodVerified = true;  // verify raster (every scene), verify texture --implicit-lod
    q.raster.fansClippedPolygons = false;  // the full-screen triangle's clipped polygon is one primitive
    q.raster.setup = DeviceProfile::Raster::Setup::Reactor;
    q.raster.subPixelBits = 4;  // limits.subPixelPrecisionBits (vulkaninfo): Chromium's legacy-precision build
    q.raster.fineDerivatives = false;  // dFdx / dFdy per quad (row 0 / column 0): verify raster, uv derivatives
    q.implicitLod = DeviceProfile::ImplicitLod::ReactorLog2Sqrt;
    q.implicitNearestShortcut = false;  // a gallivm LOD-selector shortcut
    q.loopIterationLimit = 0;  // SwiftShader's Reactor JIT has no loop limiter
    return q;
  }();
  return p;
}

namespace {
bool parseBool(std::string_view key, std::string_view v) {
  if (v == "true" || v == "1" || v == "on") return true;
  if (v == "false" || v == "0" || v == "off") return false;
  throw std::invalid_argument("profile field " + std::string(key) + ": expected true or false, got '" + std::string(v) + "'");
}
int parseInt(std::string_view key, std::string_view v, int lo, int hi) {
  int r = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), r);
  if (ec != std::errc() || end != v.data() + v.size() || r < lo || r > hi)
    throw std::invalid_argument("profile field " + std::string(key) + ": expected an integer in [" + std::to_string(lo) +
                                ", " + std::to_string(hi) + "], got '" + std::string(v) + "'");
  return r;
}
// gallivm (Mesa's sampler) or reactor (SwiftShader's SamplerCore): true for reactor.
bool parseStrategy(std::string_view key, std::string_view v) {
  if (v == "gallivm") return false;
  if (v == "reactor") return true;
  throw std::invalid_argument("profile field " + std::string(key) + ": expected gallivm or reactor, got '" + std::string(v) + "'");
}
DenormMode parseDenorm(std::string_view key, std::string_view v) {
  if (v == "preserve") return DenormMode::Preserve;
  if (v == "flush") return DenormMode::Flush;
  throw std::invalid_argument("profile field " + std::string(key) + ": expected preserve or flush, got '" + std::string(v) + "'");
}
}  // namespace

void setProfileField(DeviceProfile& p, std::string_view key, std::string_view v) {
  using M = DeviceProfile::MaskedFragmentLanes;
  if (key == "maskedFragmentLanes") {
    if (v != "sample" && v != "skip")
      throw std::invalid_argument("profile field maskedFragmentLanes: expected sample or skip, got '" + std::string(v) + "'");
    p.maskedFragmentLanes = v == "sample" ? M::Sample : M::Skip;
  } else if (key == "implicitNearestShortcut") {
    p.implicitNearestShortcut = parseBool(key, v);
  } else if (key == "computeVectorLanes") {
    p.computeVectorLanes = parseInt(key, v, 1, 64);
  } else if (key == "fragmentVectorW") {
    p.fragmentVectorW = parseInt(key, v, 1, 64);
  } else if (key == "fragmentVectorH") {
    p.fragmentVectorH = parseInt(key, v, 1, 64);
  } else if (key == "filterWeightFracBits") {
    p.filterWeightFracBits = parseInt(key, v, 0, 23);
  } else if (key == "lodFractionBits") {
    p.lodFractionBits = parseInt(key, v, 0, 23);
  } else if (key == "unorm8FixedPoint") {
    p.unorm8Path = parseBool(key, v) ? DeviceProfile::Unorm8Path::Fixed8 : DeviceProfile::Unorm8Path::Float;
  } else if (key == "unorm8Path") {
    using U = DeviceProfile::Unorm8Path;
    if (v == "float") p.unorm8Path = U::Float;
    else if (v == "fixed8") p.unorm8Path = U::Fixed8;
    else if (v == "fixed16") p.unorm8Path = U::Fixed16;
    else if (v == "floatscaled") p.unorm8Path = U::FloatScaled;
    else if (v == "reactor") p.unorm8Path = U::Reactor;
    else throw std::invalid_argument("profile field unorm8Path: expected float, fixed8, fixed16, floatscaled or reactor, got '" + std::string(v) + "'");
  } else if (key == "implicitLod") {
    using L = DeviceProfile::ImplicitLod;
    if (v == "fastlog2") p.implicitLod = L::FastLog2PerQuad;
    else if (v == "exact") p.implicitLod = L::Exact;
    else if (v == "reactor") p.implicitLod = L::ReactorLog2Sqrt;
    else throw std::invalid_argument("profile field implicitLod: expected fastlog2, exact or reactor, got '" + std::string(v) + "'");
  } else if (key == "rasterSetup") {
    p.raster.setup = parseStrategy(key, v) ? DeviceProfile::Raster::Setup::Reactor : DeviceProfile::Raster::Setup::Gallivm;
  } else if (key == "perspectiveRcp") {
    if (v == "division") p.raster.perspectiveRcp = DeviceProfile::Raster::PerspectiveRcp::Division;
    else if (v == "rcpnewton") p.raster.perspectiveRcp = DeviceProfile::Raster::PerspectiveRcp::RcpNewton;
    else throw std::invalid_argument("profile field perspectiveRcp: expected division or rcpnewton, got '" + std::string(v) + "'");
  } else if (key == "fineDerivatives") {
    p.raster.fineDerivatives = parseBool(key, v);
  } else if (key == "subPixelBits") {
    p.raster.subPixelBits = parseInt(key, v, 1, 16);
  } else if (key == "fansClippedPolygons") {
    p.raster.fansClippedPolygons = parseBool(key, v);
  } else if (key == "texAddressing") {
    p.texAddressing = parseStrategy(key, v) ? DeviceProfile::TexAddressing::Reactor : DeviceProfile::TexAddressing::Gallivm;
  } else if (key == "mipSelection") {
    p.mipSelection = parseStrategy(key, v) ? DeviceProfile::MipSelection::Reactor : DeviceProfile::MipSelection::Gallivm;
  } else if (key == "filterLerpFma") {
    p.filterLerpFma = parseBool(key, v);
  } else if (key == "loopIterationLimit") {
    p.loopIterationLimit = uint32_t(parseInt(key, v, 0, 1 << 30));
  } else if (key == "denormCompute") {
    p.denormCompute = parseDenorm(key, v);
  } else if (key == "denormFragment") {
    p.denormFragment = parseDenorm(key, v);
  } else {
    throw std::invalid_argument("unknown profile field '" + std::string(key) +
                                "' (known: maskedFragmentLanes, implicitNearestShortcut, computeVectorLanes, "
                                "fragmentVectorW, fragmentVectorH, filterWeightFracBits, lodFractionBits, "
                                "unorm8FixedPoint, unorm8Path, texAddressing, mipSelection, implicitLod, fansClippedPolygons, "
                                "rasterSetup, perspectiveRcp, subPixelBits, fineDerivatives, "
                                "denormCompute, denormFragment, "
                                "loopIterationLimit, filterLerpFma)");
  }
  p.verified = false;
  p.name += " [" + std::string(key) + "=" + std::string(v) + "]";
}

void setProfileField(DeviceProfile& p, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos)
    throw std::invalid_argument("profile field: expected KEY=VALUE, got '" + std::string(assignment) + "'");
  setProfileField(p, assignment.substr(0, eq), assignment.substr(eq + 1));
}

const DeviceProfile& profileByName(std::string_view name) {
  if (name == "lavapipe" || name == "llvmpipe") return lavapipeProfile();
  if (name == "nvidia") return nvidiaProfile();
  if (name == "swiftshader") return swiftshaderProfile();
  throw std::invalid_argument("unknown device profile '" + std::string(name) + "' (known: lavapipe, nvidia, swiftshader)");
}

const DeviceProfile& profileForDevice(std::string_view deviceName) {
  std::string n(deviceName);
  for (auto& c : n) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (n.find("nvidia") != std::string::npos) return nvidiaProfile();
  if (n.find("llvmpipe") != std::string::npos) return lavapipeProfile();
  if (n.find("swiftshader") != std::string::npos) return swiftshaderProfile();
  throw std::invalid_argument("no device profile for Vulkan device '" + std::string(deviceName) + "'");
}

}  // namespace emu
