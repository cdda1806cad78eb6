// Operation counting for the performance model (issue 19, model/shade_counts.cpp) and the roofline of a shading
// pass (bench/fis_roofline.cpp): lane types that
// wrap the emulator's N-lane types (emu/lanes.h), compute exactly what they compute, and count every
// vector operation by kind in thread-local counters. The shared shading source instantiated with them
// (namespace shadetwin::shade::counted) runs the same code path as the emulator's SIMD build (same
// IF_ANY skips per vector of 8 pixels), so counts / 8 are operations per pixel as executed. Texture
// lookups are counted per lane with the texels the filter reads (bilinear 4 per level, trilinear 8).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <bit>
#include <vector>

#include "emu/lanes.h"
#include "lanes/kernels.h"
#include "lanes/native_exact.h"
#include "lanes/sampler_bridge.h"
#include "lanes/vec.h"

namespace opcount {

// kPrivRead, kPrivWrite: a private (function-local) array read or written at an index that is not a literal (the
// dialect's arrayGet / arraySet, shade/prelude.h): lavapipe's gallivm lowers each to a scalar load per lane, a store to
// a load, select and store per lane; a GPU to local memory. Counted like the ALU kinds (per vector operation).
// kExDiv, kExSqrt: one vector of the exact-math layer's correctly rounded divisions or square roots (shade/exact_math.h
// exDiv, exSqrt; exInverseSqrt and exNormalize are one of each), counted as one operation of a class of their own
// (model/device_desc.h ex_div, ex_sqrt) rather than as the 164 and 101 operations of the portable routine
// (exactMathMix counts those: the GPUs' rate and the scheduler's window share).
enum Kind {
  kFAdd, kFMul, kFCmp, kIAlu, kIMul, kCvt, kSel, kMaskOp, kShift, kICmp, kISel, kPrivRead, kPrivWrite, kExDiv, kExSqrt,
  kTexLookup, kTexel, kTexNearest, kTexBilinear, kTexTrilinear, kTexUniform, kTexFetch, kTexLine, kTexMiss, kTexStreamMiss,
  kLoop1, kLoop2, kLoop3,  // iterations of the dialect's FOR loops at nesting depth 1, 2 and 3 or deeper (per vector)
  kKinds
};
inline const char* kKindNames[kKinds] = {"fadd", "fmul", "fcmp", "ialu", "imul", "cvt", "select", "mask", "shift", "icmp", "iselect",
                                          "private_read", "private_write", "ex_div", "ex_sqrt", "tex_lookup", "texel",
                                          "tex_nearest", "tex_bilinear", "tex_trilinear", "tex_uniform", "tex_fetch", "tex_line",
                                          "tex_miss", "tex_stream_miss", "loop1", "loop2", "loop3"};
inline thread_local std::array<uint64_t, kKinds> counts{};
inline void tick(Kind k, uint64_t n = 1) { counts[size_t(k)] += n; }

// An out-of-order core running the counted vector operations (the performance model's latency-aware ALU time,
// model/model.h): operations dispatch in program order at the device's issue rate (interval: seconds of issue per
// operation of that kind on one core), at most `window` of them in flight (a reorder window: an operation dispatches
// once the one `window` earlier has retired), each starts when its operands are ready and takes its kind's latency;
// retirement is in order. Every counted value carries the time it is ready (`t`); values from memory or constants are
// ready at once. Off unless a counted run switches it on; it never changes a computed bit.
// slots: the window entries an operation of that kind holds (1; an exact division or square root holds as many as the
// operations its portable routine counts, which the device keeps in flight as its own).
struct Scheduler {
  bool on = false;
  std::array<double, kKinds> latency{}, interval{};
  std::array<uint32_t, kKinds> slots = ones();
  uint32_t window = 256;
  static std::array<uint32_t, kKinds> ones() {
    std::array<uint32_t, kKinds> a{};
    a.fill(1);
    return a;
  }
  std::vector<double> retired;  // retire time of the last `window` operations (a ring)
  uint64_t n = 0;
  double dispatch = 0, lastRetire = 0;
  void start() {
    retired.assign(window, 0.0);
    n = 0, dispatch = 0, lastRetire = 0;
  }
  double issue(Kind k, double ready) {
    // The operation takes entries n .. n + slots - 1: it dispatches once the operation `window` entries before its last
    // one has retired (retire times are in order, so that is the latest of those its entries wait for).
    const uint32_t w = std::min(std::max(slots[size_t(k)], 1u), window);
    const uint64_t last = n + w - 1;
    double d = dispatch;
    if (last >= window) d = std::max(d, retired[last % window]);
    const double done = std::max(d, ready) + latency[size_t(k)];
    dispatch = d + interval[size_t(k)];
    lastRetire = std::max(lastRetire, done);
    for (uint32_t i = 0; i < w; ++i) retired[(n + i) % window] = lastRetire;
    n += w;
    return done;
  }
};
inline thread_local Scheduler sched;

// The texture cache (issue 19: texels and cache lines touched, so reuse between neighbouring pixels shows): the lines
// each lane's lookup reads (its filter footprint on its level or two), through a set-associative LRU cache with the
// device's line size and capacity, in the order the counted build runs the lanes (8-lane vectors in the emulator's
// tile order; one thread). tex_line counts the distinct lines of each lane's lookup, tex_miss those not in the cache;
// tex_stream_miss the misses a stream prefetcher covers: the line next to (or before) one of the last 16 misses, as
// when a pass reads rows in order (a host CPU's prefetcher follows such sequences and fetches them ahead; a scattered
// miss costs its latency; the model prices each from its own calibrate kernel).
// Addresses are the texels' host addresses (each level one contiguous allocation, rows then layers, as on a device).
struct TexCache {
  static constexpr uint32_t kWays = 16;
  uint32_t lineShift = 6;
  uint64_t sets = 0;               // 0: off
  std::vector<uint64_t> tags;      // sets x kWays, most recently used first; 0 = empty (tags are line + 1)
  uint64_t recent[16] = {};        // the last misses (lines + 1), a ring
  uint32_t nRecent = 0;
  void configure(uint32_t lineBytes, double capacityBytes) {
    lineShift = 0;
    while ((2u << lineShift) <= lineBytes) ++lineShift;
    const double lines = capacityBytes / double(1u << lineShift);
    sets = lines >= kWays ? uint64_t(lines / kWays) : 0;
    tags.assign(sets * kWays, 0);
    std::fill(std::begin(recent), std::end(recent), 0);
    nRecent = 0;
  }
  // The lookups' footprint lines: counted once each per lane (a bilinear 2x2 usually spans one or two lines).
  void lane(const uint64_t* addrs, int n) {
    uint64_t seen[16];
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const uint64_t line = addrs[i] >> lineShift;
      bool dup = false;
      for (int j = 0; j < m; ++j) dup = dup || seen[j] == line;
      if (!dup && m < 16) seen[m++] = line;
    }
    for (int j = 0; j < m; ++j) touch(seen[j]);
  }
  void touch(uint64_t line) {
    ++counts[kTexLine];
    if (!sets) return;
    uint64_t* set = tags.data() + (line * 0x9E3779B97F4A7C15ull >> 20) % sets * kWays;  // hashed index: no aliasing of
    const uint64_t tag = line + 1;                                                         // power-of-two row strides
    uint32_t w = 0;
    while (w < kWays && set[w] != tag) ++w;
    if (w == kWays) {  // a miss evicts the least recently used way
      ++counts[kTexMiss], w = kWays - 1;
      bool stream = false;
      for (uint64_t r : recent) stream = stream || (r && (r == tag - 1 || r == tag + 1));
      if (stream) ++counts[kTexStreamMiss];
      recent[nRecent++ % 16] = tag;
    }
    for (; w > 0; --w) set[w] = set[w - 1];
    set[0] = tag;
  }
};
inline thread_local TexCache texCache;

// How the device runs the dialect's IF_ANY blocks (a structured `if` in GLSL), set per counted run. false: a vector
// skips a block none of its lanes takes (a GPU's warp branches around it). true: the device runs every block under
// its lane mask and only a loop whose lanes are all inactive exits at once (lavapipe's gallivm and SwiftShader's
// SpirvShader; calibrate's branch kernels measure it), so an untaken block's straight-line operations count and the
// operations of loops inside it do not. The C++ still computes the block (IF_ANY's contract: every effect is a select
// on the mask), so no bit changes.
inline thread_local bool executeEveryBlock = false;
// The pipeline's kSceneBrdfKinds specialization constant (shade/prelude.h) for the counting build (model/counted.h):
// the BRDF kinds the scene's materials use; the others are compiled out on the GPU. Set per counted run.
inline thread_local uint32_t sceneBrdfKinds = 0xffffffffu;
// Whether the device's compiler removes a block behind a false specialization constant (DeviceDesc
// folds_specialization_constants): true, specConstantMask marks such a mask `never` (the block is not counted);
// false, it is an ordinary mask and the block counts as any untaken block does. Set per counted run.
inline thread_local bool foldsSpecConstants = true;
inline thread_local int loopDepth = 0;
inline thread_local int deadBase = -1;  // loop depth where the outermost untaken block began; -1: in none
inline bool counting() { return deadBase < 0 || loopDepth <= deadBase; }

/// Counts one vector operation of kind k whose operands are ready at `ready`; returns when its result is.
inline double op(Kind k, double ready) {
  if (!counting()) return ready;  // inside a loop of an untaken block: the device does not run it
  tick(k);
  return sched.on ? sched.issue(k, ready) : 0.0;
}

// Value numbering: the device compiler's redundancy elimination (DeviceDesc value_numbering, calibrate's shared-block
// kernels measure it). A device that turns every structured `if` into straight-line code under a mask and then numbers
// values globally computes an expression once however many of those blocks write it (the MIS techniques' brdfPdf and
// brdfEval of one direction share the half vector); without LICM (gallivm's pass list leaves it out), an expression a
// loop repeats with unchanged operands is computed in every iteration. lavapipe measured no such sharing (its two
// blocks cost 94-101% of two distinct ones), so its file has it off.
// With it on, every counted value carries a number: values read from memory, a texture or a lane-wise set() get
// fresh ones, constants one per bit pattern, an operation one per (operation, operand numbers); an operation whose
// number an operation counted earlier in the same iteration of every loop around it (or before those loops) already
// has is not counted again and is ready when that one was. Off (0 numbers) it changes nothing. It never changes a
// computed bit.
inline thread_local bool valueNumbering = false;
inline thread_local uint64_t vnNext = 1;
constexpr uint64_t kVnNone = ~0ull;      // no operand
constexpr uint64_t kVnConst = 1ull << 63;  // constants: the tag and the bits
constexpr uint32_t kVnCommutative = 1u << 31;
inline uint64_t freshVn() { return valueNumbering ? vnNext++ : 0; }
inline uint64_t constVn(uint32_t tag, uint32_t bits) { return kVnConst | (uint64_t(tag) << 32) | bits; }
// The iteration of the loop at each depth (loopIteration numbers them; depth 0: outside every loop).
inline thread_local std::array<uint64_t, 64> loopEpoch{};
inline thread_local uint64_t epochNext = 1;
// The numbered operations of the current invocation (open addressing; emptied when the driver starts the next
// invocation, or when half full).
struct VnTable {
  struct Slot {
    uint64_t a, b, c, v, epoch;
    double t;
    uint32_t code, gen, depth;
  };
  static constexpr size_t kSlots = size_t(1) << 20;
  std::vector<Slot> slots;
  uint32_t gen = 1;
  size_t used = 0;
  void reset() {
    if (slots.empty()) slots.assign(kSlots, Slot{0, 0, 0, 0, 0, 0.0, 0, 0, 0});
    ++gen, used = 0;
  }
  Slot& find(uint32_t code, uint64_t a, uint64_t b, uint64_t c) {
    uint64_t h = (a * 0x9E3779B97F4A7C15ull) ^ (b * 0xC2B2AE3D27D4EB4Full) ^ (c * 0x165667B19E3779F9ull) ^ code;
    h ^= h >> 29;
    for (size_t i = size_t(h) & (kSlots - 1);; i = (i + 1) & (kSlots - 1)) {
      Slot& e = slots[i];
      if (e.gen != gen || (e.code == code && e.a == a && e.b == b && e.c == c)) return e;
    }
  }
};
inline thread_local VnTable vnTable;
struct Res {
  double t;
  uint64_t v;
};
/// op() with value numbering: the result's ready time and number.
inline Res vop(Kind k, uint32_t code, double ready, uint64_t a, uint64_t b = kVnNone, uint64_t c = kVnNone) {
  if (!counting()) return {ready, freshVn()};
  if (!valueNumbering || a == 0 || b == 0 || c == 0) return {op(k, ready), freshVn()};
  if ((code & kVnCommutative) && a > b) std::swap(a, b);
  VnTable::Slot& e = vnTable.find(code, a, b, c);
  const uint32_t depth = uint32_t(std::min(std::max(loopDepth, 0), 63));
  if (e.gen == vnTable.gen && e.depth <= depth && loopEpoch[e.depth] == e.epoch)
    return {e.t, e.v};  // computed before, where it dominates this one: the device computes it once
  const Res r{op(k, ready), vnNext++};
  if (e.gen != vnTable.gen) ++vnTable.used;
  e = VnTable::Slot{a, b, c, r.v, loopEpoch[depth], r.t, code, vnTable.gen, depth};
  if (vnTable.used > VnTable::kSlots / 2) vnTable.reset();
  return r;
}
/// The counted driver starts an invocation (one vector of lanes): numbers do not carry over from the last one.
inline void startInvocation() {
  if (valueNumbering) vnTable.reset();
}
template <class A> inline Res vop1(Kind k, uint32_t code, const A& a) { return vop(k, code, a.t, a.v); }
template <class A, class B> inline Res vop2(Kind k, uint32_t code, const A& a, const B& b) {
  return vop(k, code, a.t > b.t ? a.t : b.t, a.v, b.v);
}
template <class A, class B, class C> inline Res vop3(Kind k, uint32_t code, const A& a, const B& b, const C& c) {
  return vop(k, code, std::max({a.t, b.t, c.t}), a.v, b.v, c.v);
}
// Operation codes: (operation << 3) | type tag (1 float, 2 uint, 3 int, 4 mask).
enum VnOp : uint32_t {
  kVnAdd = 1, kVnSub, kVnMul, kVnNeg, kVnLt, kVnLe, kVnGt, kVnGe, kVnEq, kVnNe, kVnSel, kVnAnd, kVnOr, kVnXor, kVnNot,
  kVnShl, kVnShr, kVnShlI, kVnShrI, kVnMulHi, kVnCvtI, kVnCvtU, kVnCvtF, kVnExDiv, kVnExSqrt
};
constexpr uint32_t vnCode(VnOp o, uint32_t tag, bool commutative = false) {
  return (uint32_t(o) << 3) | tag | (commutative ? kVnCommutative : 0u);
}
template <class T> inline uint32_t vnBits(T x) { return std::bit_cast<uint32_t>(x); }
inline double op(Kind k, double a, double b) { return op(k, a > b ? a : b); }
inline double op(Kind k, double a, double b, double c) { return op(k, a > b ? (a > c ? a : c) : (b > c ? b : c)); }

template <int N> struct F;
template <int N> struct U;
template <int N> struct I;

struct LoopScope {
  LoopScope() { ++loopDepth; }
  ~LoopScope() { --loopDepth; }
  LoopScope(const LoopScope&) = delete;
  LoopScope& operator=(const LoopScope&) = delete;
};
struct IfAnyScope {
  bool taken, opened;  // opened: this block began the untaken region
  IfAnyScope(bool t, bool o) : taken(t), opened(o) {}
  ~IfAnyScope() {
    if (opened) deadBase = -1;
  }
  IfAnyScope(const IfAnyScope&) = delete;
  IfAnyScope& operator=(const IfAnyScope&) = delete;
  explicit operator bool() const { return taken; }
};

template <int N>
struct M {
  emu::Mask<N> m;
  double t = 0;
  bool never = false;  // false from a uniform constant (a specialization constant: the GPU compiles the block out)
  uint64_t v = 0;      // value number (valueNumbering)
  M() = default;
  M(bool b) : m(b), never(!b), v(constVn(4, b)) {}
  explicit M(emu::Mask<N> x, double ready = 0, bool nev = false) : m(x), t(ready), never(nev), v(freshVn()) {}
  M(emu::Mask<N> x, Res r, bool nev = false) : m(x), t(r.t), never(nev), v(r.v) {}
  explicit operator bool() const = delete;
  friend M operator&&(M a, M b) { return M(a.m && b.m, vop2(kMaskOp, vnCode(kVnAnd, 4, true), a, b), a.never || b.never); }
  friend M operator||(M a, M b) { return M(a.m || b.m, vop2(kMaskOp, vnCode(kVnOr, 4, true), a, b), a.never && b.never); }
  friend M operator!(M a) { return M(!a.m, vop1(kMaskOp, vnCode(kVnNot, 4), a)); }
  friend IfAnyScope ifAnyScope(M a) {
    const bool any = anyLane(a.m);
    if (any || !executeEveryBlock || a.never) return {any, false};
    const bool outer = deadBase < 0;
    if (outer) deadBase = loopDepth;
    return {true, outer};
  }
  friend M operator==(M a, M b) { return M(a.m == b.m, vop2(kMaskOp, vnCode(kVnEq, 4, true), a, b)); }
  friend M operator!=(M a, M b) { return M(a.m != b.m, vop2(kMaskOp, vnCode(kVnNe, 4, true), a, b)); }
  friend bool anyLane(M a) { return anyLane(a.m); }
  friend F<N> select(M c, float a, float b) { return select(c, F<N>(a), F<N>(b)); }
  friend U<N> select(M c, uint32_t a, uint32_t b) { return select(c, U<N>(a), U<N>(b)); }
  friend I<N> select(M c, int32_t a, int32_t b) { return select(c, I<N>(a), I<N>(b)); }
  friend M select(M c, M a, M b) { return M(select(c.m, a.m, b.m), vop3(kISel, vnCode(kVnSel, 4), c, a, b)); }
};

#define OPCOUNT_COMMON(Self, Lane, Elem, Tag, AddKind, MulKind, CmpKind, SelKind)                                  \
  Lane x;                                                                                                  \
  double t = 0;                                                                                            \
  uint64_t v = 0; /* value number (valueNumbering) */                                                      \
  Self() = default;                                                                                        \
  Self(Elem s) : x(s), v(constVn(Tag, vnBits(s))) {}                                                       \
  explicit Self(Lane l, double ready = 0) : x(l), t(ready), v(freshVn()) {}                                \
  Self(Lane l, Res r) : x(l), t(r.t), v(r.v) {}                                                            \
  Elem operator[](int i) const { return x[i]; }                                                            \
  void set(int i, Elem e) { x.set(i, e), v = freshVn(); }                                                  \
  friend Self operator+(Self a, Self b) { return Self(a.x + b.x, vop2(AddKind, vnCode(kVnAdd, Tag, true), a, b)); } \
  friend Self operator-(Self a, Self b) { return Self(a.x - b.x, vop2(AddKind, vnCode(kVnSub, Tag), a, b)); } \
  friend Self operator*(Self a, Self b) { return Self(a.x * b.x, vop2(MulKind, vnCode(kVnMul, Tag, true), a, b)); } \
  friend Self operator-(Self a) { return Self(-a.x, vop1(AddKind, vnCode(kVnNeg, Tag), a)); }              \
  Self& operator+=(Self b) { return *this = *this + b; }                                                   \
  Self& operator-=(Self b) { return *this = *this - b; }                                                   \
  Self& operator*=(Self b) { return *this = *this * b; }                                                   \
  friend M<N> operator<(Self a, Self b) { return M<N>(a.x < b.x, vop2(CmpKind, vnCode(kVnLt, Tag), a, b)); } \
  friend M<N> operator<=(Self a, Self b) { return M<N>(a.x <= b.x, vop2(CmpKind, vnCode(kVnLe, Tag), a, b)); } \
  friend M<N> operator>(Self a, Self b) { return M<N>(a.x > b.x, vop2(CmpKind, vnCode(kVnGt, Tag), a, b)); } \
  friend M<N> operator>=(Self a, Self b) { return M<N>(a.x >= b.x, vop2(CmpKind, vnCode(kVnGe, Tag), a, b)); } \
  friend M<N> operator==(Self a, Self b) { return M<N>(a.x == b.x, vop2(CmpKind, vnCode(kVnEq, Tag, true), a, b)); } \
  friend M<N> operator!=(Self a, Self b) { return M<N>(a.x != b.x, vop2(CmpKind, vnCode(kVnNe, Tag, true), a, b)); } \
  friend Self select(M<N> m, Self a, Self b) { return Self(select(m.m, a.x, b.x), vop3(SelKind, vnCode(kVnSel, Tag), m, a, b)); }

#define OPCOUNT_INT(Self, Tag)                                                                              \
  friend Self operator&(Self a, Self b) { return Self(a.x & b.x, vop2(kIAlu, vnCode(kVnAnd, Tag, true), a, b)); } \
  friend Self operator|(Self a, Self b) { return Self(a.x | b.x, vop2(kIAlu, vnCode(kVnOr, Tag, true), a, b)); } \
  friend Self operator^(Self a, Self b) { return Self(a.x ^ b.x, vop2(kIAlu, vnCode(kVnXor, Tag, true), a, b)); } \
  friend Self operator~(Self a) { return Self(~a.x, vop1(kIAlu, vnCode(kVnNot, Tag), a)); }                \
  friend Self operator<<(Self a, Self b) { return Self(a.x << b.x, vop2(kShift, vnCode(kVnShl, Tag), a, b)); } \
  friend Self operator>>(Self a, Self b) { return Self(a.x >> b.x, vop2(kShift, vnCode(kVnShr, Tag), a, b)); } \
  friend Self operator<<(Self a, int s) {                                                                  \
    return Self(a.x << s, vop(kShift, vnCode(kVnShlI, Tag), a.t, a.v, constVn(3, uint32_t(s))));          \
  }                                                                                                        \
  friend Self operator>>(Self a, int s) {                                                                  \
    return Self(a.x >> s, vop(kShift, vnCode(kVnShrI, Tag), a.t, a.v, constVn(3, uint32_t(s))));          \
  }                                                                                                        \
  Self& operator&=(Self b) { return *this = *this & b; }                                                   \
  Self& operator|=(Self b) { return *this = *this | b; }                                                   \
  Self& operator^=(Self b) { return *this = *this ^ b; }                                                   \
  Self& operator<<=(int s) { return *this = *this << s; }                                                  \
  Self& operator>>=(int s) { return *this = *this >> s; }

template <int N>
struct U {
  OPCOUNT_COMMON(U, emu::U32<N>, uint32_t, 2, kIAlu, kIMul, kICmp, kISel)
  OPCOUNT_INT(U, 2)
  explicit U(I<N> a);
  explicit U(F<N> a);
  friend U mulHi(U a, U b) { return U(emu::mulHi(a.x, b.x), vop2(kIMul, vnCode(kVnMulHi, 2, true), a, b)); }
};

template <int N>
struct I {
  OPCOUNT_COMMON(I, emu::I32<N>, int32_t, 3, kIAlu, kIMul, kICmp, kISel)
  OPCOUNT_INT(I, 3)
  explicit I(U<N> a) : x(emu::I32<N>(a.x)), t(a.t), v(a.v) {}  // a bit cast: the same number (ops carry the type)
  explicit I(F<N> a);
};

template <int N>
struct F {
  OPCOUNT_COMMON(F, emu::F32<N>, float, 1, kFAdd, kFMul, kFCmp, kSel)
  explicit F(I<N> a) : F(emu::F32<N>(a.x), vop1(kCvt, vnCode(kVnCvtF, 3), a)) {}
  explicit F(U<N> a) : F(emu::F32<N>(a.x), vop1(kCvt, vnCode(kVnCvtF, 2), a)) {}
};

template <int N> inline LoopScope loopScope(F<N>) { return {}; }
// Each iteration of the dialect's FOR: what it computes is its own (value numbering: no LICM). Counted by its depth
// (the model's loop-state term: model/spirv_loops.h), unless inside a loop of an untaken block (the device skips it).
template <int N> inline void loopIteration(F<N>) {
  if (loopDepth >= 0 && loopDepth < 64) loopEpoch[size_t(loopDepth)] = epochNext++;
  if (loopDepth >= 1 && counting()) tick(Kind(std::min<int>(kLoop1 + loopDepth - 1, kLoop3)));
}
// The dialect's specMask (shade/prelude.h): a uniform mask from a specialization constant.
template <int N> inline M<N> specConstantMask(F<N>, bool b) {
  return M<N>(emu::Mask<N>(b), 0, !b && foldsSpecConstants);
}
// The dialect's uniformMask: a run-time value no compiler folds, so a block behind a false one counts as any untaken
// block does (on a device that runs every block: its straight-line operations).
template <int N> inline M<N> runtimeUniformMask(F<N>, bool b) { return M<N>(emu::Mask<N>(b), 0, false); }

// The dialect's min/max (shade/prelude.h): counted as the compare and select they were written as (a GPU's min is one
// operation, but the calibrated classes price it so), the value the emulator's min/max instruction gives.
template <int N> inline F<N> minMachine(F<N> a, F<N> b) {
  const F<N> s = select(a < b, a, b);
  return F<N>(emu::minMachine(a.x, b.x), Res{s.t, s.v});
}
template <int N> inline F<N> maxMachine(F<N> a, F<N> b) {
  const F<N> s = select(b < a, a, b);
  return F<N>(emu::maxMachine(a.x, b.x), Res{s.t, s.v});
}

// The dialect's arrayGet / arraySet (shade/prelude.h): the element read (ready one read after the element was) or the
// value written (the write issues once the value is ready), each counted as one vector operation.
template <int N> inline F<N> indexedRead(F<N> v) { return F<N>(v.x, op(kPrivRead, v.t)); }
template <int N> inline I<N> indexedRead(I<N> v) { return I<N>(v.x, op(kPrivRead, v.t)); }
template <int N> inline U<N> indexedRead(U<N> v) { return U<N>(v.x, op(kPrivRead, v.t)); }
template <int N> inline F<N> indexedWrite(F<N> v) { return F<N>(v.x, op(kPrivWrite, v.t)); }
template <int N> inline I<N> indexedWrite(I<N> v) { return I<N>(v.x, op(kPrivWrite, v.t)); }
template <int N> inline U<N> indexedWrite(U<N> v) { return U<N>(v.x, op(kPrivWrite, v.t)); }

template <int N> U<N>::U(I<N> a) : x(emu::U32<N>(a.x)), t(a.t), v(a.v) {}
template <int N> U<N>::U(F<N> a) : U(emu::U32<N>(a.x), vop1(kCvt, vnCode(kVnCvtU, 1), a)) {}
template <int N> I<N>::I(F<N> a) : I(emu::I32<N>(a.x), vop1(kCvt, vnCode(kVnCvtI, 1), a)) {}

#undef OPCOUNT_COMMON
#undef OPCOUNT_INT

// Bit casts are free (no instruction on either build).
template <int N> inline U<N> floatBitsToUint(F<N> a) { return U<N>(emu::floatBitsToUint(a.x), Res{a.t, a.v}); }
template <int N> inline I<N> floatBitsToInt(F<N> a) { return I<N>(emu::floatBitsToInt(a.x), Res{a.t, a.v}); }
template <int N> inline F<N> uintBitsToFloat(U<N> a) { return F<N>(emu::uintBitsToFloat(a.x), Res{a.t, a.v}); }
template <int N> inline F<N> intBitsToFloat(I<N> a) { return F<N>(emu::intBitsToFloat(a.x), Res{a.t, a.v}); }

/// N texel fetches (one texel each at integer coordinates, no sampler), unless inside a loop of an untaken block: a
/// class of their own (tex_fetch), not a nearest textureLod, which scales, wraps and selects a level first (lavapipe:
/// 0.75x the fetch rate, calibrate kinds 6 and 26, session 39).
inline void countFetches(int n) {
  if (!counting()) return;
  tick(kTexLookup, uint64_t(n));
  tick(kTexel, uint64_t(n));
  tick(kTexFetch, uint64_t(n));
}

/// The dialect's texelFetchUniform: one texel at coordinates every lane shares, fetched per lane by a software device
/// (its rate is calibrate's uniform-fetch kernel), once per warp by a GPU. Counted per lane.
template <int N> inline void countUniformFetches(F<N>) {
  if (counting()) tick(kTexUniform, uint64_t(N));
}

/// The host addresses of the texels textureLod(u, v, layer, lod) reads (Vulkan's texel selection, spec "Texel
/// Filtering": level(s) from the clamped LOD and the mipmap mode, the 2x2 (linear) or 1 (nearest) texels about
/// (u w - 0.5, v h - 0.5) wrapped per address mode); up to 8 into `out`, returns how many. Non-finite inputs read the
/// first texel (what they read does not matter to the cache, only that something is read).
inline int texelAddresses(const emu::Texture& tex, const emu::SamplerDesc& s, float u, float v, float layer, float lod,
                          uint64_t* out) {
  if (!std::isfinite(u) || !std::isfinite(v)) u = v = 0.0f;
  if (!std::isfinite(lod)) lod = 0.0f;
  const float maxLevel = float(tex.levelCount() - 1);
  const float l = std::fmin(std::fmax(lod + s.lodBias, std::fmax(s.minLod, 0.0f)), std::fmin(s.maxLod, maxLevel));
  const bool linear = (l > 0.0f ? s.minFilter : s.magFilter) == emu::Filter::Linear;
  uint32_t levels[2] = {0, 0};
  int nLevels = 1;
  if (s.mipmapMode == emu::MipmapMode::Nearest) {
    levels[0] = uint32_t(std::fmin(std::floor(l + 0.5f), maxLevel));
  } else {
    levels[0] = uint32_t(std::floor(l));
    if (float(levels[0]) < l && levels[0] + 1 <= uint32_t(maxLevel)) levels[1] = levels[0] + 1, nLevels = 2;
  }
  const int32_t ly = int32_t(std::fmin(std::fmax(std::floor(std::isfinite(layer) ? layer + 0.5f : 0.0f), 0.0f),
                                       float(tex.layers() - 1)));
  auto wrap = [](int32_t i, int32_t n, emu::AddressMode m) {
    if (m == emu::AddressMode::Repeat) return ((i % n) + n) % n;
    return std::min(std::max(i, 0), n - 1);  // clamp to edge (mirrored repeat: the same lines to within one texel)
  };
  int n = 0;
  for (int k = 0; k < nLevels; ++k) {
    const int32_t w = int32_t(tex.levelWidth(levels[k])), h = int32_t(tex.levelHeight(levels[k]));
    const float x = u * float(w) - (linear ? 0.5f : 0.0f), y = v * float(h) - (linear ? 0.5f : 0.0f);
    const int32_t x0 = int32_t(std::fmax(std::fmin(std::floor(x), 1e9f), -1e9f));
    const int32_t y0 = int32_t(std::fmax(std::fmin(std::floor(y), 1e9f), -1e9f));
    for (int dy = 0; dy < (linear ? 2 : 1); ++dy)
      for (int dx = 0; dx < (linear ? 2 : 1); ++dx)
        out[n++] = uint64_t(reinterpret_cast<uintptr_t>(tex.texelPtr(levels[k], uint32_t(ly), uint32_t(wrap(x0 + dx, w, s.addressU)),
                                                                      uint32_t(wrap(y0 + dy, h, s.addressV)))));
  }
  return n;
}

/// A texelFetch's texel of each lane through the texture cache (coordinates are in range: the dialect's contract).
template <class X, class Y, class L>
inline void fetchLines(const emu::Texture& tex, const X& x, const Y& y, const L& layer, int level, int n) {
  if (!counting()) return;
  for (int i = 0; i < n; ++i) {
    const uint64_t a = uint64_t(reinterpret_cast<uintptr_t>(tex.texelPtr(uint32_t(level), uint32_t(layer[i]), uint32_t(x[i]),
                                                                         uint32_t(y[i]))));
    texCache.lane(&a, 1);
  }
}

/// Texels a linear-filtered lookup at `lod` reads on a texture of `levels` levels: 4 per level, two
/// levels when the LOD falls strictly between levels (trilinear), one otherwise.
inline uint64_t texelsRead(float lod, uint32_t levels) {
  const float l = std::fmin(std::fmax(lod, 0.0f), float(levels - 1));
  return (l > 0.0f && l < float(levels - 1) && l != std::floor(l)) ? 8 : 4;
}

}  // namespace opcount

// The sampler bridge for the counted lanes (qualified calls from the C++ prelude resolve here).
namespace shadetwin::shade {
template <int N>
V4<opcount::F<N>> textureLodLanes(const Sampler2D& s, opcount::F<N> u, opcount::F<N> v, opcount::F<N> lod,
                                  opcount::F<N> layer = opcount::F<N>(0.0f)) {
  if (opcount::counting()) {  // not inside a loop of an untaken block
    opcount::tick(opcount::kTexLookup, N);
    const bool nearest = s.desc.magFilter == emu::Filter::Nearest && s.desc.minFilter == emu::Filter::Nearest;
    for (int i = 0; i < N; ++i) {
      const uint64_t texels = opcount::texelsRead(lod[i], s.tex->levelCount());
      opcount::tick(opcount::kTexel, nearest ? 1 : texels);
      const bool twoLevels = texels == 8 && s.desc.mipmapMode == emu::MipmapMode::Linear;
      opcount::tick(nearest ? opcount::kTexNearest : twoLevels ? opcount::kTexTrilinear : opcount::kTexBilinear);
      uint64_t addrs[8];
      opcount::texCache.lane(addrs, opcount::texelAddresses(*s.tex, s.desc, u.x[i], v.x[i], layer.x[i], lod.x[i], addrs));
    }
  }
  const V4<emu::F32<N>> r = textureLodLanes(s, u.x, v.x, lod.x, layer.x);
  const double t = std::max({u.t, v.t, lod.t, layer.t});  // the lookup's own cost is the texture term, not the schedule
  return V4<opcount::F<N>>(opcount::F<N>(r.x, t), opcount::F<N>(r.y, t), opcount::F<N>(r.z, t), opcount::F<N>(r.w, t));
}
template <int N>
V4<opcount::F<N>> texelFetchLanes(const Sampler2D& s, opcount::I<N> x, opcount::I<N> y, int level,
                                   opcount::I<N> layer = opcount::I<N>(0)) {
  opcount::countFetches(N);
  opcount::fetchLines(*s.tex, x.x, y.x, layer.x, level, N);
  const V4<emu::F32<N>> r = texelFetchLanes(s, x.x, y.x, level, layer.x);
  const double t = std::max({x.t, y.t, layer.t});
  return V4<opcount::F<N>>(opcount::F<N>(r.x, t), opcount::F<N>(r.y, t), opcount::F<N>(r.z, t), opcount::F<N>(r.w, t));
}
template <int N>
void uintFetchLanes(const USampler2DArray& s, opcount::I<N> x, opcount::I<N> y, opcount::I<N> layer, int level, opcount::U<N>& a,
                    opcount::U<N>& b, opcount::U<N>& c, opcount::U<N>& d) {
  opcount::countFetches(N);
  opcount::fetchLines(*s.tex, x.x, y.x, layer.x, level, N);
  emu::U32<N> ra, rb, rc, rd;
  uintFetchLanes(s, x.x, y.x, layer.x, level, ra, rb, rc, rd);
  a.x = ra, b.x = rb, c.x = rc, d.x = rd;
  a.t = b.t = c.t = d.t = std::max({x.t, y.t, layer.t});
  a.v = opcount::freshVn(), b.v = opcount::freshVn(), c.v = opcount::freshVn(), d.v = opcount::freshVn();  // loaded
}
}  // namespace shadetwin::shade

// The counted build's exact division and square root (shade/exact_math.h exDiv, exSqrt, through their C++-only fast
// path): one ex_div or ex_sqrt operation, its value the emulator's own (lanes/kernels.h exactDivLanes: the same
// correctly rounded bits as the portable routine a GPU runs). With opcount::countPortableExactMath set, the fast path
// is off and the portable routine's own operations count instead (exactMathMix: the classes it is made of).
namespace opcount {
inline thread_local bool countPortableExactMath = false;
}
namespace shadetwin::shade {
template <int N>
inline NativeResult<opcount::F<N>> nativeDiv(opcount::F<N> a, opcount::F<N> b) {
  if (opcount::countPortableExactMath) return {false, opcount::F<N>(0.0f)};
  float xa[N], xb[N], q[N];
  for (int i = 0; i < N; ++i) xa[i] = a.x[i], xb[i] = b.x[i];
  exactDivLanes(xa, xb, q, N);
  opcount::F<N> r(0.0f);
  for (int i = 0; i < N; ++i) r.x.set(i, q[i]);
  const opcount::Res o = opcount::vop2(opcount::kExDiv, opcount::vnCode(opcount::kVnExDiv, 1), a, b);
  r.t = o.t, r.v = o.v;
  return {true, r};
}
template <int N>
inline NativeResult<opcount::F<N>> nativeSqrt(opcount::F<N> x) {
  if (opcount::countPortableExactMath) return {false, opcount::F<N>(0.0f)};
  float xs[N], q[N];
  for (int i = 0; i < N; ++i) xs[i] = x.x[i];
  exactSqrtLanes(xs, q, N);
  opcount::F<N> r(0.0f);
  for (int i = 0; i < N; ++i) r.x.set(i, q[i]);
  const opcount::Res o = opcount::vop1(opcount::kExSqrt, opcount::vnCode(opcount::kVnExSqrt, 1), x);
  r.t = o.t, r.v = o.v;
  return {true, r};
}
}  // namespace shadetwin::shade
