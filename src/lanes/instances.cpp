// Compiles every shared shading header in all C++ instantiations (scalar, x4, x8, x16) and exposes
// the verify kernels to the host.
#include "lanes/instantiate.h"

#include <algorithm>
#include <stdexcept>

#include "emu/fpenv.h"
#include "lanes/kernels.h"

namespace shadetwin {
namespace {

template <int N, class Eval>
void runLanes(Eval eval, int fn, const float* in, float* out, size_t n) {
  using F = emu::F32<N>;
  using V3 = shade::V3<F>;
  for (size_t base = 0; base < n; base += N) {
    V3 v(F(0.0f), F(0.0f), F(0.0f));
    size_t count = std::min<size_t>(N, n - base);
    for (size_t l = 0; l < count; ++l) {
      v.x.set(int(l), in[3 * (base + l)]);
      v.y.set(int(l), in[3 * (base + l) + 1]);
      v.z.set(int(l), in[3 * (base + l) + 2]);
    }
    V3 r = eval(fn, v);
    for (size_t l = 0; l < count; ++l) {
      out[3 * (base + l)] = r.x[int(l)];
      out[3 * (base + l) + 1] = r.y[int(l)];
      out[3 * (base + l) + 2] = r.z[int(l)];
    }
  }
}

}  // namespace

void evalMathKernel(int fn, const float* in, float* out, size_t n, int lanes, bool flushDenormals) {
  if (fn < 0 || fn >= shade::scalar::kMathCount) throw std::invalid_argument("evalMathKernel: unknown kernel");
  emu::DenormalScope mode(flushDenormals);
  switch (lanes) {
    case 1:
      for (size_t i = 0; i < n; ++i) {
        auto r = shade::scalar::evalMath(fn, shade::V3<float>(in[3 * i], in[3 * i + 1], in[3 * i + 2]));
        out[3 * i] = r.x;
        out[3 * i + 1] = r.y;
        out[3 * i + 2] = r.z;
      }
      break;
    case 4: runLanes<4>([](int f, auto v) { return shade::x4::evalMath(f, v); }, fn, in, out, n); break;
    case 8: runLanes<8>([](int f, auto v) { return shade::x8::evalMath(f, v); }, fn, in, out, n); break;
    case 16: runLanes<16>([](int f, auto v) { return shade::x16::evalMath(f, v); }, fn, in, out, n); break;
    default: throw std::invalid_argument("evalMathKernel: lanes must be 1, 4, 8 or 16");
  }
}

namespace {
// f(a, b) on n lanes: the scalar build for one, else the x8 build 8 at a time (a tail padded with 1 and cut off).
template <class Scalar, class X8>
void binaryLanes(Scalar scalar, X8 x8, const float* a, const float* b, float* out, size_t n) {
  if (n == 1) {
    out[0] = scalar(a[0], b[0]);
    return;
  }
  for (size_t base = 0; base < n; base += 8) {
    emu::F32<8> va(1.0f), vb(1.0f);
    const size_t count = std::min<size_t>(8, n - base);
    for (size_t l = 0; l < count; ++l) va.set(int(l), a[base + l]), vb.set(int(l), b[base + l]);
    const emu::F32<8> r = x8(va, vb);
    for (size_t l = 0; l < count; ++l) out[base + l] = r[int(l)];
  }
}
}  // namespace

void exactDivLanes(const float* a, const float* b, float* out, size_t n) {
  binaryLanes([](float x, float y) { return shade::scalar::exDiv(x, y); },
              [](emu::F32<8> x, emu::F32<8> y) { return shade::x8::exDiv(x, y); }, a, b, out, n);
}

void exactSqrtLanes(const float* x, float* out, size_t n) {
  binaryLanes([](float v, float) { return shade::scalar::exSqrt(v); },
              [](emu::F32<8> v, emu::F32<8>) { return shade::x8::exSqrt(v); }, x, x, out, n);
}

int mathKernelCount() { return shade::scalar::kMathCount; }

const char* mathKernelName(int fn) {
  static const char* names[] = {"div", "sqrt", "inversesqrt", "normalize", "exp", "exp2", "log",
                                "log2", "pow", "sin", "cos", "atan2", "acos"};
  static_assert(sizeof(names) / sizeof(names[0]) == shade::scalar::kMathCount);
  return (fn >= 0 && fn < mathKernelCount()) ? names[fn] : "?";
}

}  // namespace shadetwin
