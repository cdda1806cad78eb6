// C++ side of the dialect: 2/3/4-vectors over a lane type T (float or emu::F32<N>), with the GLSL
// operators. Operators are hidden friends, so a uniform `float` converts to T on either side.
#pragma once

#include <xmmintrin.h>

namespace shadetwin::shade {

template <class T>
struct V2 {
  T x, y;
  V2() = default;
  explicit V2(T s) : x(s), y(s) {}
  V2(T x_, T y_) : x(x_), y(y_) {}
  friend V2 operator+(V2 a, V2 b) { return V2(a.x + b.x, a.y + b.y); }
  friend V2 operator-(V2 a, V2 b) { return V2(a.x - b.x, a.y - b.y); }
  friend V2 operator*(V2 a, V2 b) { return V2(a.x * b.x, a.y * b.y); }
  friend V2 operator*(V2 a, T s) { return V2(a.x * s, a.y * s); }
  friend V2 operator*(T s, V2 a) { return V2(s * a.x, s * a.y); }
  friend V2 operator-(V2 a) { return V2(-a.x, -a.y); }
};

template <class T>
struct V3 {
  T x, y, z;
  V3() = default;
  explicit V3(T s) : x(s), y(s), z(s) {}
  V3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  friend V3 operator+(V3 a, V3 b) { return V3(a.x + b.x, a.y + b.y, a.z + b.z); }
  friend V3 operator-(V3 a, V3 b) { return V3(a.x - b.x, a.y - b.y, a.z - b.z); }
  friend V3 operator*(V3 a, V3 b) { return V3(a.x * b.x, a.y * b.y, a.z * b.z); }
  friend V3 operator*(V3 a, T s) { return V3(a.x * s, a.y * s, a.z * s); }
  friend V3 operator*(T s, V3 a) { return V3(s * a.x, s * a.y, s * a.z); }
  friend V3 operator-(V3 a) { return V3(-a.x, -a.y, -a.z); }
};

template <class T>
struct V4 {
  T x, y, z, w;
  V4() = default;
  explicit V4(T s) : x(s), y(s), z(s), w(s) {}
  V4(T x_, T y_, T z_, T w_) : x(x_), y(y_), z(z_), w(w_) {}
  V4(V3<T> v, T w_) : x(v.x), y(v.y), z(v.z), w(w_) {}
  friend V4 operator+(V4 a, V4 b) { return V4(a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w); }
  friend V4 operator-(V4 a, V4 b) { return V4(a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w); }
  friend V4 operator*(V4 a, V4 b) { return V4(a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w); }
  friend V4 operator*(V4 a, T s) { return V4(a.x * s, a.y * s, a.z * s, a.w * s); }
  friend V4 operator*(T s, V4 a) { return V4(s * a.x, s * a.y, s * a.z, s * a.w); }
  friend V4 operator-(V4 a) { return V4(-a.x, -a.y, -a.z, -a.w); }
};

// Scalar-instantiation primitives (the lane types in emu/lanes.h provide the same names via ADL).
inline float select(bool m, float a, float b) { return m ? a : b; }
inline uint32_t select(bool m, uint32_t a, uint32_t b) { return m ? a : b; }
inline int32_t select(bool m, int32_t a, int32_t b) { return m ? a : b; }
inline bool select(bool m, bool a, bool b) { return m ? a : b; }
inline bool anyLane(bool m) { return m; }
// The dialect's min/max hooks (shade/prelude.h; emu/lanes.h minMachine): MINSS / MAXSS themselves, `a < b ? a : b` and
// `a > b ? a : b`, so a flushing stage's DAZ reads a subnormal operand as zero as the devices' FMin/FMax do.
inline float minMachine(float a, float b) { return _mm_cvtss_f32(_mm_min_ss(_mm_set_ss(a), _mm_set_ss(b))); }
inline float maxMachine(float a, float b) { return _mm_cvtss_f32(_mm_max_ss(_mm_set_ss(a), _mm_set_ss(b))); }
// The dialect's IF_ANY and FOR hooks (shade/prelude.h): nothing for the scalar and emulator builds.
inline bool ifAnyScope(bool m) { return m; }
inline int loopScope(float) { return 0; }
inline void loopIteration(float) {}
inline bool specConstantMask(float, bool b) { return b; }
inline bool runtimeUniformMask(float, bool b) { return b; }
inline void countUniformFetches(float) {}
// The dialect's arrayGet / arraySet hooks: the value itself.
inline float indexedRead(float v) { return v; }
inline int32_t indexedRead(int32_t v) { return v; }
inline uint32_t indexedRead(uint32_t v) { return v; }
inline float indexedWrite(float v) { return v; }
inline int32_t indexedWrite(int32_t v) { return v; }
inline uint32_t indexedWrite(uint32_t v) { return v; }
inline uint32_t floatBitsToUint(float x) { return __builtin_bit_cast(uint32_t, x); }
inline int32_t floatBitsToInt(float x) { return __builtin_bit_cast(int32_t, x); }
inline float uintBitsToFloat(uint32_t x) { return __builtin_bit_cast(float, x); }
inline float intBitsToFloat(int32_t x) { return __builtin_bit_cast(float, x); }
inline uint32_t mulHi(uint32_t a, uint32_t b) { return uint32_t((uint64_t(a) * b) >> 32); }

}  // namespace shadetwin::shade
