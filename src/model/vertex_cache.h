// A driver's post-transform vertex cache over a draw's index stream (issue 19: the performance model's vertex runs).
// SwiftShader's vertex routine checks a direct-mapped cache one index at a time and, on a miss, shades a SIMD width of
// consecutive index-stream entries at once, writing all of them to the cache (the first last, so it stays); each
// batch of primitives a worker takes starts cold (in practice: the batch objects are reused across far-apart parts of
// the stream). What a mesh's vertex order costs there follows from its index values: a sphere whose rows are 257
// vertices long maps a triangle's vertices a and a + 257 to one slot (1.5 runs a triangle), the same triangles with
// the vertices numbered in narrow strips 0.5. The model counts the runs; calibrate measures a run's cost from two such
// draws of identical triangles and pixels.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "model/device_desc.h"

namespace shadetwin::model {

/// Vertex routine runs for one draw of `indices` (triangle list) under `c`; 0 when c.entries is 0 (not simulated).
inline uint64_t vertexCacheRuns(const std::vector<uint32_t>& indices, const VertexCacheDesc& c) {
  if (!c.entries) return 0;
  std::vector<uint64_t> tag(c.entries);
  const size_t batch = size_t(c.batchTriangles) * 3;
  uint64_t runs = 0;
  for (size_t b0 = 0; b0 < indices.size(); b0 += batch) {
    const size_t end = std::min(indices.size(), b0 + batch);
    std::fill(tag.begin(), tag.end(), ~uint64_t(0));  // no index matches an empty slot
    for (size_t i = b0; i < end; ++i) {
      const uint32_t v = indices[i];
      if (tag[v & (c.entries - 1)] == v) continue;
      ++runs;
      for (size_t j = std::min<size_t>(end, i + c.runLanes); j-- > i;) tag[indices[j] & (c.entries - 1)] = indices[j];
    }
  }
  return runs;
}

}  // namespace shadetwin::model
