// Device profiles: everything Vulkan leaves to the implementation that the emulator must reproduce.
// Behaviour differences between devices live here, never in #ifdefs (docs/DESIGN.md, "Profiles").
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace emu {

enum class Stage { Compute, Fragment };
enum class DenormMode { Preserve, Flush };

struct DeviceProfile {
  std::string name;
  bool verified;             // every field below measured bit-exact on the device
  std::string provenance;    // where the values come from
  // Texture unit, float path (its lerp form: filterLerpFma below).
  int filterWeightFracBits;  // 0: exact float weights (x - floor(x)); n: weights rounded to n fraction bits
  int lodFractionBits;       // 0: exact lod fraction
  // Texture unit, 8-bit path. Fixed8 (lavapipe): RGBA8 filtered in 8.8 fixed point when both wrap
  // modes are clamp-to-edge or repeat (Mesa's AoS sampler), otherwise the float path. Fixed16
  // (SwiftShader's SamplerCore, every RGBA8 lookup): 0.16 fixed-point coordinates, texels as b << 8,
  // bilinear weights as products of 16-bit fractions, mip blend with a 16-bit truncated fraction,
  // result float(c) * (1.0f / 0xFF00) (emu/sampler_reactor.h). Float: the float path on texels
  // b * (1.0f / 255). FloatScaled: the float path on texels float(b << 8), the result scaled by
  // 1.0f / 0xFF00 (SwiftShader's 32-bit filtering of normalized formats). Reactor (SwiftShader, whose
  // samplers filter in high precision): Fixed16 for FILTER_POINT (mag and min nearest), else FloatScaled.
  enum class Unorm8Path { Float, Fixed8, Fixed16, FloatScaled, Reactor };
  Unorm8Path unorm8Path;
  // Lane grouping of the sampler's per-vector decisions (need lerp, need linear): compute invocations
  // i / computeVectorLanes; fragment pixels in blocks of fragmentVectorW x fragmentVectorH. 1 x 1 (and
  // computeVectorLanes 1) means per-lane decisions.
  int computeVectorLanes;
  int fragmentVectorW, fragmentVectorH;
  // Lanes of a fragment vector that its run does not cover (a 4x2 block that a primitive edge splits
  // is shaded once per primitive, the other primitive's pixels masked; emu::fragmentLanes). Sample
  // (lavapipe): masked lanes still run the sampler and take part in the run's per-vector decisions;
  // their inputs are what the stage gives masked lanes (buffer loads return 0), and for texture()
  // they share their quad's implicit LOD in that run (a quad the run does not cover at all gets the
  // LOD of its masked lanes' own coordinates). Skip: masked lanes take no part.
  enum class MaskedFragmentLanes { Sample, Skip } maskedFragmentLanes;
  // Denormals per shader stage.
  DenormMode denormCompute;
  DenormMode denormFragment;
  // Rasterizer (emu/raster.h). Sub-pixel snapping of window coordinates to subPixelBits fraction
  // bits (round to nearest even), top-left coverage rule, plane equations of each attribute from the
  // float vertex positions, evaluated at pixel centres with fused (interpFma) or separate mul + add.
  struct Raster {
    int subPixelBits;
    bool viewportFma;     // x_win = fma(x_ndc, scale, translate) instead of mul then add
    bool interpFma;       // a = fma(dadx, x, a0); a = fma(dady, y, a)
    bool cwSwapsLast;     // clockwise triangles are set up as (v0, v2, v1) (else (v1, v0, v2))
    bool fineDerivatives; // dFdx per quad row / dFdy per column (else coarse: row 0 / column 0)
    // Clipping. GuardBand: only the near (z >= 0) and far (z <= w) planes cut triangles; x/y are
    // left to the scissor (a GPU with a guard band larger than any viewport). DrawModule: Mesa's
    // draw-module clipper (what lavapipe runs, no guard band): a vertex outside any of the six planes
    // sends the triangle through Sutherland-Hodgman in plane order x <= w, x >= -w, y <= w, y >= -w,
    // z >= 0, z <= w (only the planes some vertex violates), the polygon fanned from its first vertex.
    enum class Clip { GuardBand, DrawModule } clip;
    bool clipFromNearer;   // a new vertex is interpolated from the endpoint nearer the plane (else from the outside one)
    bool clipViewportFma;  // window position of a new vertex with fused mul + add (lavapipe: C code, separate)
    // A clipped polygon is rasterized as the triangles of a fan from its first vertex, each its own
    // primitive for fragment vectors and quads (lavapipe's draw module); else as one primitive
    // (SwiftShader's rasterizer takes the clipped polygon whole; a guard-band GPU never cuts x/y).
    bool fansClippedPolygons = true;
    bool verified;
    // Triangle setup and interpolation. Gallivm (llvmpipe): see emu/raster.h. Reactor (SwiftShader's
    // VertexRoutine, SetupRoutine, QuadRasterizer and PixelRoutine): X = rint(X0xF + (x_c (1/w)) WxF)
    // in subPixelBits fixed point (X0xF = X0 2^b - 2^(b-1), WxF = W 2^b); the plane equations relative to
    // vertex 0 after rotating the minimum clip y, then the maximum clip w, first, from
    // M = [rhw0-scaled barycentric rows] of x_i = (w_i 2^-b) X_i, a = x1 y2 - x2 y1 (one division);
    // per pixel D = C + y' B per row, v = D + x' A (x', y' relative to vertex 0), perspective
    // attributes times the reciprocal of the interpolated 1/w (perspectiveRcp), all separate mul/add.
    enum class Setup { Gallivm, Reactor } setup = Setup::Gallivm;
    // Reactor's perspective reciprocal: Division (1 / w) or RcpNewton (rcpps scaled to be exact at powers
    // of two, then one Newton step (r + r) - (w r) r: the host CPU's rcpps table, which the emulator
    // reads on the same machine).
    enum class PerspectiveRcp { Division, RcpNewton } perspectiveRcp = PerspectiveRcp::Division;
  } raster;
  // Implicit LOD of texture() in fragment shaders (emu::implicitLod). FastLog2PerQuad (lavapipe):
  // derivatives per 2x2 quad (top-right - top-left, bottom-left - top-left), rho^2 = max over x/y of
  // (ds*W)^2 + (dt*H)^2, lod = 0.5 * fastlog2(rho^2) with fastlog2(x) = (exponent - 1) + mantissa in [1, 2).
  // Exact: 0.5 * log2(rho^2), per pixel with the stage's derivatives (unverified stand-in).
  // ReactorLog2Sqrt (SwiftShader, SamplerCore::computeLod + log2sqrt): the same per-quad rho^2, then
  // lod = (float(bits(rho^2 * rho^2)) - 0x3F800000) * 2^-25, the bit pattern of rho^4 read as an
  // integer (rounded to float) for 4 log2(rho) (piecewise linear in the mantissa).
  enum class ImplicitLod { FastLog2PerQuad, Exact, ReactorLog2Sqrt } implicitLod;
  bool implicitLodVerified;
  // Integer level shortcut of texture() (gallivm's LOD selector, lp_build_ilog2_sqrt): with mip filter
  // nearest and no post-log2 adjustment (sampler bias 0, minLod <= 0, maxLod >= 15) the level is
  // (exponent(rho^2) + 1) >> 1 and the min/mag choice rho^2 > 1, instead of rint of the LOD above.
  // The two differ where rho^2 = 2^(4j+1) (the LOD's tie j + 1/2 rounds to even). Measured with
  // `verify texture --implicit-lod` (docs/DESIGN.md s3, issue 14).
  bool implicitNearestShortcut;
  // Loop back-edges one shader invocation may take, all loops together (0: unlimited). lavapipe:
  // gallivm's loop limiter, LP_MAX_TGSI_LOOP_ITERATIONS = 65535, shared by every loop of a function;
  // past it every loop exits, so a kernel that loops longer returns partial sums (measured with the
  // glints lighting table: docs/RESULTS.md). Drivers split such work so no invocation reaches it.
  uint32_t loopIterationLimit;
  // Float-path filter lerp: true, one fused fma(w, b - a, a) (lavapipe); false, a + w (b - a) as a
  // separate multiply and add (SwiftShader's SamplerCore blends, issue 18).
  bool filterLerpFma = true;
  // Texture unit strategies: whose arithmetic each stage of the sampler follows (docs/DESIGN.md s3).
  // Addressing. Gallivm (Mesa lp_bld_sample): clamp as max(min(u W, W) - 1/2, 0), repeat of a
  // power-of-two size as floor(u W - 1/2) & (W - 1), else frac(u) W, mirror 2|u/2 - rint(u/2)|.
  // Reactor (SwiftShader SamplerCore::address): u first mapped into [0, 1) (clamp to [0, 1 - 2^-24],
  // frac for repeat, mirror min(2 |u/2 - rint(u/2)|, 1 - 2^-24)), then scaled; nearest truncates,
  // linear floors u W - 1/2 and clamps or wraps the two indices.
  enum class TexAddressing { Gallivm, Reactor };
  TexAddressing texAddressing = TexAddressing::Gallivm;
  // LOD to levels. Gallivm: min/max clamps (minLod only when > 0), linear mip fraction zeroed where a
  // level index is clamped, levels lerp only where some lane of the SIMD vector needs it (vector
  // decisions above). Reactor: lod clamped to [minLod, maxLod] (both first clamped to [0, 13]);
  // linear mip reads trunc(lod) and trunc(lod) + 1 (the view repeats its last level) and always blends
  // with frac(lod), even at fraction 0 (an inf texel then gives NaN); nearest mip rint(lod); the
  // min/mag choice of mixed filters from the clamped lod; every lane decides alone; a one-level view with
  // equal mag/min filters samples at LOD 0.
  enum class MipSelection { Gallivm, Reactor };
  MipSelection mipSelection = MipSelection::Gallivm;
  DenormMode denorm(Stage s) const { return s == Stage::Compute ? denormCompute : denormFragment; }
};

const DeviceProfile& lavapipeProfile();
const DeviceProfile& nvidiaProfile();
/// SwiftShader (issue 18), verified: its texture unit and rasterizer as Reactor strategies, 4 sub-pixel bits, coarse
/// derivatives, denormals flushed in both stages, no loop limit (docs/DESIGN.md s3).
const DeviceProfile& swiftshaderProfile();
/// Profile by name ("lavapipe", "nvidia"); throws std::invalid_argument listing the known names.
const DeviceProfile& profileByName(std::string_view name);
/// Sets one field by name to an alternative value ("maskedFragmentLanes" = sample|skip,
/// "implicitNearestShortcut" = true|false, "computeVectorLanes", "fragmentVectorW", "fragmentVectorH" =
/// integer, "filterWeightFracBits", "lodFractionBits" = integer, "unorm8Path" = float|fixed8|fixed16|floatscaled|reactor
/// ("unorm8FixedPoint" = true|false: fixed8|float), "texAddressing", "mipSelection" = gallivm|reactor,
/// "implicitLod" = fastlog2|exact|reactor, "fansClippedPolygons" = true|false,
/// "denormCompute", "denormFragment" = preserve|flush, "loopIterationLimit" = integer), to measure what the profile's choice is worth.
/// The profile is then marked unverified. Throws std::invalid_argument naming the key or the value.
void setProfileField(DeviceProfile& p, std::string_view key, std::string_view value);
/// "KEY=VALUE" form of setProfileField.
void setProfileField(DeviceProfile& p, std::string_view assignment);
/// Profile for a Vulkan device name ("llvmpipe ..." -> lavapipe, "NVIDIA ..." -> nvidia).
const DeviceProfile& profileForDevice(std::string_view deviceName);

}  // namespace emu
