// The shadetwin shading dialect: one source, compiled as GLSL 4.50 (glslc) and as C++ (once per lane
// type, see src/lanes/instantiate.h). Shared shading headers include nothing else.
//
// Rules of the dialect (docs/DESIGN.md, "The dialect"):
//   - Per-lane values: Float, Float2, Float3, Float4, Int, Uint, Mask. Uniform values (loop counters,
//     constants): float, int, uint. Float literals carry the f suffix (1.0f).
//   - Only .x/.y/.z/.w and constructors on vectors; no multi-letter swizzles.
//   - No `if`/`?:`/`while` on a Mask: use select(m, a, b) (a where m). Loops run a uniform count.
//     IF_ANY(m) { x = select(m, f(...), x); } skips work no lane needs (C++: when no lane of the
//     vector has m; GLSL: per invocation). Every effect inside must be a select on m, so the result
//     never depends on which lanes share a vector. A branch on a uniform setting is IF_ANY(uniformMask(c)) with the
//     same selects, not `if (c)`: the software devices run its untaken side too, and the counting build counts it so.
//   - No raw '/', sqrt, inversesqrt, normalize, exp, log, pow, sin, cos, fma, mix, dot, length in
//     shared code: the exact-math layer (exact_math.h) and the dialect's own dot/cross/lerp are
//     the only sources of those. The C++ lane types have no operator/, so a raw '/' fails the build.
//   - Declare locals with PRECISE; the build also marks every float operation NoContraction in SPIR-V.
//   - Out parameters: OUT(T) / INOUT(T), assigned first; prefer returning a struct.
//   - A loop whose trip count is not a small literal is written FOR (init; cond; step): GLSL `for`; in C++ the
//     same loop, which the counting build (model/op_count.h) sees entered and left. A device that runs every
//     block of an `if` under its mask still leaves such a loop at once when no lane is active, while its
//     compiler unrolls a loop of a small literal count (plain `for`: exact_math's 26 and 27 steps, Philox's 10
//     rounds) into straight-line code that runs (calibrate's branch kernels measure both), so the performance
//     model counts an untaken block's straight-line code and unrolled loops, not its FOR loops.
//   - A local array indexed by anything but a literal or the counter of a literal loop (a FOR loop's variable, a value
//     computed from one) is read with arrayGet(a, i) and written with arraySet(a, i, v): GLSL a[i] and a[i] = v; the
//     counting build counts them (private_read / private_write: a device without registers addressable by index pays
//     per lane, lavapipe a scalar load per lane and a masked store per lane; docs/DESIGN.md §13). tests/dialect_test
//     fails on a shared header that indexes a local array by a FOR loop's variable without them.
#ifndef SHADE_PRELUDE_GLSL_DONE
#ifdef GL_core_profile
#define SHADE_PRELUDE_GLSL_DONE 1

#define Float float
#define Float2 vec2
#define Float3 vec3
#define Float4 vec4
#define Int int
#define Uint uint
#define Mask bool
#define PRECISE precise
#define OUT(T) out T
#define INOUT(T) inout T
#define INLINE
#define IF_ANY(m) if (m)
#define FOR for
#define Sampler2D sampler2D
#define Sampler2DArray sampler2DArray

// BRDF kinds the scene's materials use (bit k set: kind k, shade/brdf.h), a specialization constant
// the host sets per pipeline (passes/shade_vk.cpp), so the code of kinds no material has is not
// compiled at all (a GPU runs both sides of a divergent branch under a mask; lavapipe does for every
// branch). Default: every kind. The C++ builds skip absent kinds at run time (IF_ANY) instead.
layout(constant_id = 0) const uint kSceneBrdfKinds = 0xffffffffu;
// SPEC_INT(name, id, value): an int the host may set per pipeline (GLSL: specialization constant `id`,
// which may size a local array, so a kernel's scratch fits the frame's setting; C++: the constant, the
// capacity every setting fits).
#define SPEC_INT(name, id, value) layout(constant_id = id) const int name = value;

// specMask(b): a mask from a specialization constant (the same for every lane, fixed when the pipeline is built).
bool specMask(bool b) { return b; }
// uniformMask(b): a mask from a value every invocation shares at run time (a push constant, a settings field).
bool uniformMask(bool b) { return b; }
// select(m, a, b): a where m is true, else b. GLSL mix() with a bool selector picks without arithmetic.
float select(bool m, float a, float b) { return mix(b, a, m); }
vec2 select(bool m, vec2 a, vec2 b) { return mix(b, a, bvec2(m)); }
vec3 select(bool m, vec3 a, vec3 b) { return mix(b, a, bvec3(m)); }
vec4 select(bool m, vec4 a, vec4 b) { return mix(b, a, bvec4(m)); }
int select(bool m, int a, int b) { return mix(b, a, m); }
uint select(bool m, uint a, uint b) { return mix(b, a, m); }
bool select(bool m, bool a, bool b) { return mix(b, a, m); }
// Exact-math fast paths: the C++ builds use the CPU's IEEE operation where it gives the same bits
// (src/lanes/native_exact.h); a GPU always runs the portable recurrence.
struct NativeResult { bool ok; float value; };
NativeResult nativeDiv(float a, float b) { return NativeResult(false, 0.0f); }
NativeResult nativeSqrt(float x) { return NativeResult(false, 0.0f); }
// texelFetch of a 2D texture with separate coordinates (the C++ side has no ivec2).
vec4 texelFetch2D(sampler2D s, int x, int y, int level) { return texelFetch(s, ivec2(x, y), level); }
// texelFetch at uniform coordinates (the same texel for every invocation: a table row).
vec4 texelFetchUniform(sampler2D s, int x, int y, int level) { return texelFetch(s, ivec2(x, y), level); }
// texelFetch of a 2D array texture with separate coordinates.
vec4 texelFetchLayer(sampler2DArray s, int x, int y, int layer, int level) { return texelFetch(s, ivec3(x, y, layer), level); }
// An integer texture (RGBA32UI: usampler2DArray), read only by texelFetch, exactly.
#define USampler2DArray usampler2DArray
struct UintTexel4 {
  uint x;
  uint y;
  uint z;
  uint w;
};
UintTexel4 texelFetchLayerU(usampler2DArray s, int x, int y, int layer, int level) {
  uvec4 t = texelFetch(s, ivec3(x, y, layer), level);
  return UintTexel4(t.x, t.y, t.z, t.w);
}
// textureLod of a 2D array texture with the layer apart, and the size of its level 0 as floats.
vec4 textureLodLayer(sampler2DArray s, vec2 uv, float layer, float lod) { return textureLod(s, vec3(uv, layer), lod); }
vec2 textureSizeOf(sampler2DArray s) {
  ivec3 z = textureSize(s, 0);
  return vec2(float(z.x), float(z.y));
}
#define dot st_dot
#define cross st_cross
// A local array at a non-literal index (see the rules above).
#define arrayGet(a, i) (a)[i]
#define arraySet(a, i, v) (a)[i] = (v)

uint mulHi(uint a, uint b) {
  uint hi;
  uint lo;
  umulExtended(a, b, hi, lo);
  return hi;
}
// Explicit evaluation order, no fusion: ((x*x + y*y) + z*z) + w*w.
float st_dot(vec2 a, vec2 b) { precise float r = a.x * b.x + a.y * b.y; return r; }
float st_dot(vec3 a, vec3 b) { precise float r = (a.x * b.x + a.y * b.y) + a.z * b.z; return r; }
float st_dot(vec4 a, vec4 b) {
  precise float r = ((a.x * b.x + a.y * b.y) + a.z * b.z) + a.w * b.w;
  return r;
}
vec3 st_cross(vec3 a, vec3 b) {
  precise vec3 r = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  return r;
}
#endif  // GL_core_profile
#endif  // SHADE_PRELUDE_GLSL_DONE

#ifndef GL_core_profile
// ---- C++: this part is included once per lane type, inside a namespace that has defined
// Float, Int, Uint and Mask (see instantiate.h). Everything below is per instantiation. ----
#define PRECISE
#define OUT(T) T&
#define INOUT(T) T&
#define INLINE inline
// ifAnyScope(m): anyLane(m) for the emulator's masks; an object that also tells the counting build (model/op_count.h)
// where the block ends. loopScope, loopIteration: nothing, or the counting build's markers of a loop and of each of
// its iterations.
#define IF_ANY(m) if ([[maybe_unused]] auto if_any_scope_ = ifAnyScope(m); if_any_scope_)
#define FOR(...) \
  if ([[maybe_unused]] auto loop_scope_ = loopScope(Float()); true) for (__VA_ARGS__) if (loopIteration(Float()); true)
#define SPEC_INT(name, id, value) const int name = value;
// specMask(b): a mask from a specialization constant; the counting build marks a false one compiled out on devices
// whose compilers specialize (model/op_count.h specConstantMask).
inline Mask specMask(bool b) { return specConstantMask(Float(), b); }
// uniformMask(b): a mask from a value every invocation shares at run time. A block that only some settings run is
// written IF_ANY(uniformMask(c)) { x = select(m, ..., x); }, not `if (c)`: the software devices run a block behind a
// false uniform condition too (calibrate, with kind 10's condition a push constant: 109% of its work on lavapipe, 149%
// on SwiftShader; docs/RESULTS.md session 41), and the counting build counts it only as an IF_ANY block.
inline Mask uniformMask(bool b) { return runtimeUniformMask(Float(), b); }

using Float2 = ::shadetwin::shade::V2<Float>;
using Float3 = ::shadetwin::shade::V3<Float>;
using Float4 = ::shadetwin::shade::V4<Float>;
using uint = uint32_t;
using Sampler2D = ::shadetwin::shade::Sampler2D;
inline Float4 textureLod(const Sampler2D& s, Float2 uv, Float lod) {
  return ::shadetwin::shade::textureLodLanes(s, uv.x, uv.y, lod);
}
#ifndef SHADE_RUNTIME_BRDF_KINDS
inline constexpr uint32_t kSceneBrdfKinds = 0xffffffffu;  // GLSL: a specialization constant
#else
// The counting build (model/counted.h) takes the pipeline's value at run time: it counts what the GPU compiled.
#define kSceneBrdfKinds SHADE_RUNTIME_BRDF_KINDS
#endif
using NativeResult = ::shadetwin::shade::NativeResult<Float>;
inline NativeResult nativeDiv(Float a, Float b) { return ::shadetwin::shade::nativeDiv(a, b); }
inline NativeResult nativeSqrt(Float x) { return ::shadetwin::shade::nativeSqrt(x); }
using Sampler2DArray = ::shadetwin::shade::Sampler2D;  // the emulated texture has layers
inline Float4 textureLodLayer(const Sampler2DArray& s, Float2 uv, Float layer, Float lod) {
  return ::shadetwin::shade::textureLodLanes(s, uv.x, uv.y, lod, layer);
}
// One load broadcast to every lane (a GPU's uniform fetch; the emulator loads once, not per lane; the counting build
// counts it: countUniformFetches).
inline Float4 texelFetchUniform(const Sampler2D& s, int x, int y, int level) {
  countUniformFetches(Float());
  const ::shadetwin::shade::V4<float> t = ::shadetwin::shade::texelFetchLanes(s, int32_t(x), int32_t(y), level);
  return Float4(Float(t.x), Float(t.y), Float(t.z), Float(t.w));
}
// A local array at a non-literal index (see the rules above): the element, counted by the counting build (indexedRead,
// indexedWrite: model/op_count.h; nothing in the scalar and emulator builds).
template <class T, size_t K>
inline T arrayGet(const T (&a)[K], int i) {
  return indexedRead(a[i]);
}
template <class T, size_t K, class V>
inline void arraySet(T (&a)[K], int i, V v) {
  a[i] = indexedWrite(T(v));
}
inline Float4 texelFetchLayer(const Sampler2DArray& s, Int x, Int y, Int layer, int level) {
  return ::shadetwin::shade::texelFetchLanes(s, x, y, level, layer);
}
inline Float2 textureSizeOf(const Sampler2DArray& s) { return Float2(Float(float(s.tex->width())), Float(float(s.tex->height()))); }
using USampler2DArray = ::shadetwin::shade::USampler2DArray;
struct UintTexel4 {
  Uint x;
  Uint y;
  Uint z;
  Uint w;
};
inline UintTexel4 texelFetchLayerU(const USampler2DArray& s, Int x, Int y, Int layer, int level) {
  UintTexel4 r;
  ::shadetwin::shade::uintFetchLanes(s, x, y, layer, level, r.x, r.y, r.z, r.w);
  return r;
}
inline Float4 texelFetch2D(const Sampler2D& s, Int x, Int y, int level) {
  return ::shadetwin::shade::texelFetchLanes(s, x, y, level);
}
// Implicit LOD from the quad (fragment stage, SIMD builds only: lanes are whole 2x2 quads).
template <class F = Float>
inline ::shadetwin::shade::V4<F> texture(const Sampler2D& s, ::shadetwin::shade::V2<F> uv) {
  return ::shadetwin::shade::textureImplicitLanes(s, uv.x, uv.y);
}

inline Float abs(Float x) { return uintBitsToFloat(floatBitsToUint(x) & 0x7fffffffu); }
// GLSL min: y if y < x, else x; max: y if x < y, else x. The machine's min/max (emu/lanes.h minMachine), not a select:
// under a flushing stage's DAZ they read a subnormal as zero, as the devices' FMin/FMax do, at any optimisation level.
inline Float min(Float a, Float b) { return minMachine(b, a); }
inline Float max(Float a, Float b) { return maxMachine(b, a); }
inline Int min(Int a, Int b) { return select(b < a, b, a); }
inline Int max(Int a, Int b) { return select(a < b, b, a); }
inline Uint min(Uint a, Uint b) { return select(b < a, b, a); }
inline Uint max(Uint a, Uint b) { return select(a < b, b, a); }
inline Float clamp(Float x, Float lo, Float hi) { return min(max(x, lo), hi); }
inline Int clamp(Int x, Int lo, Int hi) { return min(max(x, lo), hi); }
/// floor per IEEE: exact for every input (|x| >= 2^23 is already integral; NaN stays NaN).
inline Float floor(Float x) {
  Float t = Float(Int(x));
  t = select(t > x, t - 1.0f, t);
  return select(abs(x) < 8388608.0f, t, x);
}
inline Float fract(Float x) { return x - floor(x); }
inline Float dot(Float2 a, Float2 b) { return a.x * b.x + a.y * b.y; }
inline Float dot(Float3 a, Float3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
inline Float dot(Float4 a, Float4 b) { return ((a.x * b.x + a.y * b.y) + a.z * b.z) + a.w * b.w; }
inline Float3 cross(Float3 a, Float3 b) {
  return Float3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline Float2 select(Mask m, Float2 a, Float2 b) { return Float2(select(m, a.x, b.x), select(m, a.y, b.y)); }
inline Float3 select(Mask m, Float3 a, Float3 b) {
  return Float3(select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z));
}
inline Float4 select(Mask m, Float4 a, Float4 b) {
  return Float4(select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z), select(m, a.w, b.w));
}
#endif  // !GL_core_profile
