// Compile-only checks (ctest): each CASE_ must fail to compile; with no CASE_ it must compile.
#include "lanes/instantiate.h"

namespace shadetwin::shade::x8 {
inline Float probe(Float a, Float b) {
#if defined(CASE_mask_branch)
  if (a < b) return a;  // per-lane branch: must not compile
  return b;
#elif defined(CASE_mask_ternary)
  return (a < b) ? a : b;  // per-lane ternary: must not compile
#elif defined(CASE_raw_division)
  return a / b;  // raw division: must go through exDiv
#else
  return select(a < b, a, exDiv(a, b));
#endif
}
}  // namespace shadetwin::shade::x8

int main() { return 0; }
