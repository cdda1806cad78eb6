// The loop-state term's reading of a module (issue 19, model/spirv_loops.h): each loop's nesting depth and the values
// it carries from one iteration to the next (its header's OpPhi components), on hand-built modules whose answer is
// known by construction and on the shipped modules whose loops the source fixes.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "model/spirv_loops.h"

#include "calibrate_carried_64.inc"
#include "calibrate_carried_8.inc"
#include "sh_project_comp.inc"
#include "shade_fis_comp.inc"
#include "visibility_filter_comp.inc"
#include "visibility_fit_comp.inc"

namespace {
using namespace shadetwin::model;

// A tiny module builder: the header, then instructions (opcode, operands).
struct Module {
  std::vector<uint32_t> w{0x07230203u, 0x00010000u, 0u, 100u, 0u};
  void op(uint32_t code, std::vector<uint32_t> operands) {
    w.push_back(uint32_t(operands.size() + 1) << 16 | code);
    w.insert(w.end(), operands.begin(), operands.end());
  }
};
enum : uint32_t { kFloat = 1, kVec3 = 2, kUint = 3, kStruct = 4, kArr = 5, kFour = 6 };

// Types: float, vec3, uint, struct {vec3, float, uint} (5 components), float[4] (4).
Module typed() {
  Module m;
  m.op(22, {kFloat, 32});
  m.op(23, {kVec3, kFloat, 3});
  m.op(21, {kUint, 32, 0});
  m.op(30, {kStruct, kVec3, kFloat, kUint});
  m.op(43, {kUint, kFour, 4});
  m.op(28, {kArr, kFloat, kFour});
  return m;
}
void label(Module& m, uint32_t id) { m.op(248, {id}); }
void loopMerge(Module& m, uint32_t merge, uint32_t cont) { m.op(246, {merge, cont, 0}); }
void phi(Module& m, uint32_t type, uint32_t id) { m.op(245, {type, id, 90, 91}); }

TEST(SpirvLoops, DepthsAndCarriedValuesOfNestedAndSiblingLoops) {
  Module m = typed();
  m.op(54, {0, 10, 0, 0});  // OpFunction
  label(m, 20);             // entry
  label(m, 21);             // outer loop header: a vec3 and a uint
  phi(m, kVec3, 40), phi(m, kUint, 41);
  loopMerge(m, 25, 24);
  label(m, 22);  // inner loop header (inside 21..25): the struct and the array
  phi(m, kStruct, 42), phi(m, kArr, 43);
  loopMerge(m, 24, 23);
  label(m, 23);  // inner continue
  label(m, 24);  // inner merge = outer continue
  label(m, 25);  // outer merge
  label(m, 26);  // a sibling loop after the first: depth 1 again, one float
  phi(m, kFloat, 44);
  loopMerge(m, 28, 27);
  label(m, 27);
  label(m, 28);
  phi(m, kVec3, 45);  // a phi outside every loop header (a merge block's): carried by no loop
  m.op(56, {});       // OpFunctionEnd
  const std::vector<SpirvLoop> loops = spirvLoops(m.w);
  ASSERT_EQ(loops.size(), 3u);
  EXPECT_EQ(loops[0].depth, 1u); EXPECT_EQ(loops[0].carried, 4u);
  EXPECT_EQ(loops[1].depth, 2u); EXPECT_EQ(loops[1].carried, 9u);
  EXPECT_EQ(loops[2].depth, 1u); EXPECT_EQ(loops[2].carried, 1u);
  EXPECT_EQ(carriedByDepth(m.w), (std::vector<uint32_t>{4, 9, 0}));
}

TEST(SpirvLoops, DepthsBeyondTheLastArePooled) {
  Module m = typed();
  m.op(54, {0, 10, 0, 0});
  // Four nested loops, headers 30..33, merges 43..40 (innermost first), carrying 1, 2, 3 and 7 floats.
  const uint32_t carried[4] = {1, 2, 3, 7};
  for (uint32_t d = 0; d < 4; ++d) {
    label(m, 30 + d);
    for (uint32_t k = 0; k < carried[d]; ++k) phi(m, kFloat, 50 + 10 * d + k);
    loopMerge(m, 43 - d, 60 + d);
  }
  for (uint32_t d = 0; d < 4; ++d) label(m, 40 + d);
  m.op(56, {});
  const std::vector<SpirvLoop> loops = spirvLoops(m.w);
  ASSERT_EQ(loops.size(), 4u);
  for (uint32_t d = 0; d < 4; ++d) {
    EXPECT_EQ(loops[d].depth, d + 1);
    EXPECT_EQ(loops[d].carried, carried[d]);
  }
  EXPECT_EQ(carriedByDepth(m.w), (std::vector<uint32_t>{1, 2, 7}));  // depth 3 and 4 pooled: the most
}

TEST(SpirvLoops, NotSpirvOrTruncatedIsAnError) {
  const std::vector<uint32_t> text{0x6c6c6568u, 0x6f77206fu, 0x646c72u, 0u, 0u};
  EXPECT_THROW(spirvLoops(text), std::runtime_error);
  Module m = typed();
  m.w.push_back(5u << 16 | 245u);  // an OpPhi of 5 words with 1 present
  m.w.push_back(kFloat);
  try {
    spirvLoops(m.w);
    FAIL() << "a truncated module was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated instruction"), std::string::npos) << e.what();
  }
}

// The shipped modules, as their sources write them (after spirv-opt -O):
// - calibrate_carried.comp: 8 or 64 accumulators, x and the counter;
// - sh_project.comp (shade/sh_irradiance.h shProjectRow): one loop over the row's texels carrying the 16 RGB
//   coefficients (48 floats) and the column;
// - visibility_fit.comp (shade/visibility.h): one loop over the K maps; visibility_filter.comp two nested loops (dy, dx);
// - shade_fis.comp: the sample loop carries the RGB sum and the counter (4).
TEST(SpirvLoops, ShippedModules) {
  EXPECT_EQ(carriedByDepth(kSpv_calibrate_carried_8), (std::vector<uint32_t>{10, 0, 0}));
  EXPECT_EQ(carriedByDepth(kSpv_calibrate_carried_64), (std::vector<uint32_t>{66, 0, 0}));
  const std::vector<SpirvLoop> sh = spirvLoops(kSpv_sh_project_comp);
  ASSERT_EQ(sh.size(), 1u);
  EXPECT_EQ(sh[0].depth, 1u); EXPECT_EQ(sh[0].carried, 49u);
  const std::vector<SpirvLoop> fit = spirvLoops(kSpv_visibility_fit_comp);
  ASSERT_EQ(fit.size(), 1u);
  EXPECT_EQ(fit[0].depth, 1u);
  const std::vector<SpirvLoop> filter = spirvLoops(kSpv_visibility_filter_comp);
  ASSERT_EQ(filter.size(), 2u);
  EXPECT_EQ(filter[0].depth, 1u); EXPECT_EQ(filter[1].depth, 2u);
  const std::vector<uint32_t> fis = carriedByDepth(kSpv_shade_fis_comp);
  EXPECT_EQ(fis[0], 4u);
}

}  // namespace
