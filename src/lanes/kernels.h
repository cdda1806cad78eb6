// Host entry points into the C++ instantiations of the shared shading code (src/lanes/instances.cpp).
#pragma once
#include <cstddef>

namespace shadetwin {

/// Evaluates verify kernel `fn` (kMath* in shade/verify_kernels.h) on `n` inputs of 3 floats
/// (a, b, c), writing 3 floats each. lanes = 1 runs the scalar `float` build; 4, 8 or 16 run the
/// SIMD build of that width (a tail shorter than the width is padded and cut off).
/// flushDenormals runs the code with FTZ/DAZ set, as a stage whose device flushes (lavapipe fragment).
void evalMathKernel(int fn, const float* in, float* out, size_t n, int lanes, bool flushDenormals = false);

/// The exact-math layer's division a[i] / b[i] and square root sqrt(x[i]) (shade/exact_math.h exDiv, exSqrt: correctly
/// rounded, the bits the portable routine gives on every device), n lanes through the x8 build (n = 1: the scalar
/// build). The performance model's counting lanes take their values from here (model/op_count.h).
void exactDivLanes(const float* a, const float* b, float* out, size_t n);
void exactSqrtLanes(const float* x, float* out, size_t n);

/// Number of verify-math kernels and their names.
int mathKernelCount();
const char* mathKernelName(int fn);

}  // namespace shadetwin
