// Kd-tree partition of an environment map for importance sampling (issue 5, item 1), after the
// block-selection scheme the issue describes: start from the whole map, repeatedly take the block with
// the largest sum of squared errors SSE = sum(w^2) - (sum w)^2 / n and split it at the position, along
// either axis, that maximizes lSum^2/lSize + rSum^2/rSize (equivalently: minimizes the children's total
// SSE, since SSE_children = sum(w^2) - lSum^2/lSize - rSum^2/rSize), until `blocks` blocks exist or no
// block has SSE > 0. Summed-area tables of w and w^2 make every block sum O(1), so one split costs
// O(width + height) and the build O(blocks (W + H) + W H).
//
// The weight w of a texel (the choice the issue asks to document): the largest luminance (Rec. 709:
// 0.2126 R + 0.7152 G + 0.0722 B, clamped at 0) among the texel and its 8 neighbours (wrap in u,
// clamp in v), times sin(theta) of the texel centre, theta the polar angle of the equirectangular
// row. sin(theta) makes w proportional to the texel's share of the sphere; the neighbourhood maximum
// makes the piecewise-constant pdf bound the radiance the shaders integrate, which is the bilinear
// interpolation of the texels (a lookup inside a texel blends its neighbours). With the texel's own
// luminance, a dim texel next to the sun of city.exr receives up to half the sun's radiance through
// the bilinear blend at a pdf 10^4 times smaller: fireflies (measured: PSNR 23.7 dB instead of
// 36 dB for inversion-mis at 16 sample pairs, docs/RESULTS.md). Negative luminance (real in the CC0
// maps) carries no probability.
#pragma once
#include <cstdint>
#include <vector>

namespace shadetwin {

struct EnvBlock {
  uint32_t x0, y0, x1, y1;  // texel rectangle [x0, x1) x [y0, y1)
  double sum = 0;           // sum of w over the block
  double sse = 0;           // sum of squared errors of w about the block's mean
  uint32_t texels() const { return (x1 - x0) * (y1 - y0); }
};

struct EnvKdTree {
  uint32_t width = 0, height = 0;
  std::vector<EnvBlock> blocks;  // a partition of the map, in the order they were made
  double total = 0;              // sum of w over the map
};

/// The texel weights w (width * height, rows top to bottom) of an RGBA float equirectangular map.
std::vector<double> envSamplingWeights(const float* rgba, uint32_t width, uint32_t height);

/// Builds the partition into at most `blocks` blocks (>= 1). Throws std::invalid_argument on a zero
/// size or a weight count that does not match.
EnvKdTree buildEnvKdTree(const std::vector<double>& w, uint32_t width, uint32_t height, uint32_t blocks);

}  // namespace shadetwin

namespace shadetwin {

// ---- Block distribution (issue 5, item 2) ----
// Blocks are ranked by mean weight (sum / texels), brightest first, and block rank k in [0, n) is
// drawn from the one-parameter density over x in [0, n)
//   p(x) = 1 / (log(1 + n/alpha) (alpha + x)),     (integral over [0, n) = 1 for every alpha > 0)
// by inversion of its CDF F(x) = log(1 + x/alpha) / log(1 + n/alpha):  x = alpha ((1 + n/alpha)^xi - 1),
// k = floor(x). Block k's probability is the integral of p over [k, k + 1):
//   P_k(alpha) = log(1 + 1/(alpha + k)) / log(1 + n/alpha).
// alpha -> infinity is the uniform choice; alpha -> 0 puts all mass on the brightest blocks. The
// direction is a uniform point of the block in (u, v), so its solid-angle pdf is
//   P_k W H / (texels_k 2 pi^2 sin theta)    (d omega = 2 pi^2 sin theta du dv).
// alpha is fitted to the empirical probabilities e_k = sum_k / total (in rank order) by minimizing
// the L1 misfit sum_k |P_k(alpha) - e_k|.

/// Block indices ordered by mean weight, brightest first (ties: lower index first).
std::vector<uint32_t> blocksByMean(const EnvKdTree& t);

/// P_k(alpha) above, for block rank k of n (alpha > 0).
double fittedBlockProbability(double alpha, uint32_t n, uint32_t k);

/// sum_k |P_k(alpha) - e_k| over the n = e.size() ranks.
double blockFitL1(const std::vector<double>& e, double alpha);

struct BlockFit {
  double alpha = 1;
  double l1 = 0;  // misfit at alpha
};

/// alpha minimizing blockFitL1 over [1e-6, 1e6 n]: a scan of 256 log-spaced points, then golden-
/// section search (in log alpha) in the bracket around the best point. e.size() >= 1.
BlockFit fitBlockAlpha(const std::vector<double>& e);

}  // namespace shadetwin
