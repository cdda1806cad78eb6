#include "model/spirv_loops.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace shadetwin::model {

namespace {
// Opcodes (SPIR-V 1.6 specification, section 3.52).
enum : uint32_t {
  kOpFunctionEnd = 56, kOpTypeBool = 20, kOpTypeInt = 21, kOpTypeFloat = 22, kOpTypeVector = 23,
  kOpTypeMatrix = 24, kOpTypeArray = 28, kOpTypeStruct = 30, kOpConstant = 43, kOpPhi = 245, kOpLoopMerge = 246,
  kOpLabel = 248
};
}  // namespace

std::vector<SpirvLoop> spirvLoops(std::span<const uint32_t> m) {
  if (m.size() < 5 || m[0] != 0x07230203u) throw std::runtime_error("spirvLoops: not a SPIR-V module (magic number)");
  std::unordered_map<uint32_t, uint32_t> components;  // type id -> scalar components
  std::unordered_map<uint32_t, uint32_t> constants;   // 32-bit integer constant id -> value (array lengths)
  struct Block {
    uint32_t label = 0, merge = 0, carried = 0;
  };
  std::vector<SpirvLoop> loops;
  std::vector<Block> blocks;  // the current function's, in layout order
  auto endFunction = [&] {
    std::unordered_map<uint32_t, size_t> at;
    for (size_t i = 0; i < blocks.size(); ++i) at[blocks[i].label] = i;
    std::vector<std::pair<size_t, size_t>> spans;  // [header, merge) of each loop
    for (size_t i = 0; i < blocks.size(); ++i)
      if (blocks[i].merge) {
        const auto e = at.find(blocks[i].merge);
        spans.push_back({i, e == at.end() ? blocks.size() : e->second});
      }
    size_t s = 0;
    for (size_t i = 0; i < blocks.size(); ++i)
      if (blocks[i].merge) {
        uint32_t depth = 1;
        for (size_t o = 0; o < s; ++o) depth += spans[o].first < i && spans[o].second > i;
        loops.push_back({depth, blocks[i].carried});
        ++s;
      }
    blocks.clear();
  };
  for (size_t i = 5; i < m.size();) {
    const uint32_t words = m[i] >> 16, op = m[i] & 0xffffu;
    if (words == 0 || i + words > m.size())
      throw std::runtime_error("spirvLoops: truncated instruction at word " + std::to_string(i));
    const uint32_t* w = &m[i];
    auto comp = [&](uint32_t type) {
      const auto c = components.find(type);
      return c == components.end() ? 1u : c->second;
    };
    switch (op) {
      case kOpTypeBool: case kOpTypeInt: case kOpTypeFloat: components[w[1]] = 1; break;
      case kOpTypeVector: case kOpTypeMatrix: if (words >= 4) components[w[1]] = comp(w[2]) * w[3]; break;
      case kOpTypeArray:
        if (words >= 4) {
          const auto n = constants.find(w[3]);
          components[w[1]] = comp(w[2]) * (n == constants.end() ? 1u : n->second);
        }
        break;
      case kOpTypeStruct: {
        uint32_t n = 0;
        for (uint32_t k = 2; k < words; ++k) n += comp(w[k]);
        components[w[1]] = n;
        break;
      }
      case kOpConstant: if (words == 4) constants[w[2]] = w[3]; break;
      case kOpLabel: blocks.push_back({w[1], 0, 0}); break;
      case kOpPhi: if (!blocks.empty()) blocks.back().carried += comp(w[1]); break;
      case kOpLoopMerge: if (!blocks.empty() && words >= 2) blocks.back().merge = w[1]; break;
      case kOpFunctionEnd: endFunction(); break;
      default: break;
    }
    i += words;
  }
  return loops;
}

std::vector<uint32_t> carriedByDepth(std::span<const uint32_t> module) {
  std::vector<uint32_t> d(kLoopDepths, 0);
  for (const SpirvLoop& l : spirvLoops(module)) {
    uint32_t& x = d[std::min<size_t>(l.depth, kLoopDepths) - 1];
    x = std::max(x, l.carried);
  }
  return d;
}

}  // namespace shadetwin::model
