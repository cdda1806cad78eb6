#include "inputs/env_kdtree.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <stdexcept>

namespace shadetwin {

std::vector<double> envSamplingWeights(const float* rgba, uint32_t width, uint32_t height) {
  std::vector<double> lum(size_t(width) * height);
  for (size_t i = 0; i < lum.size(); ++i) {
    const float* t = rgba + 4 * i;
    const double l = 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
    lum[i] = std::isfinite(l) && l > 0 ? l : 0.0;
  }
  // Max over the 3 x 3 neighbourhood (wrap in u, clamp in v): the texels a bilinear lookup inside
  // this texel can blend.
  std::vector<double> w(lum.size());
  for (uint32_t y = 0; y < height; ++y) {
    const double s = std::sin((y + 0.5) * std::numbers::pi / height);
    for (uint32_t x = 0; x < width; ++x) {
      double m = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        const uint32_t yy = uint32_t(std::clamp(int(y) + dy, 0, int(height) - 1));
        for (int dx = -1; dx <= 1; ++dx) {
          const uint32_t xx = uint32_t((int(x) + dx + int(width)) % int(width));
          m = std::max(m, lum[size_t(yy) * width + xx]);
        }
      }
      w[size_t(y) * width + x] = m * s;
    }
  }
  return w;
}

namespace {
// Summed-area table with a zero border: S(x, y) = sum over [0, x) x [0, y).
struct Sat {
  uint32_t W, H;
  std::vector<double> s;
  Sat(const std::vector<double>& v, uint32_t w, uint32_t h, bool squared) : W(w), H(h), s(size_t(w + 1) * (h + 1), 0.0) {
    for (uint32_t y = 0; y < h; ++y) {
      double row = 0;
      for (uint32_t x = 0; x < w; ++x) {
        const double a = v[size_t(y) * w + x];
        row += squared ? a * a : a;
        s[size_t(y + 1) * (w + 1) + x + 1] = s[size_t(y) * (w + 1) + x + 1] + row;
      }
    }
  }
  double at(uint32_t x, uint32_t y) const { return s[size_t(y) * (W + 1) + x]; }
  double rect(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const {
    return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
  }
};

struct Split {
  bool ok = false;
  bool alongX = false;  // true: cut between columns (x = pos)
  uint32_t pos = 0;
};

// The cut of block b maximizing lSum^2/lSize + rSum^2/rSize over both axes (ties: the first found,
// x before y, low positions first).
Split bestSplit(const Sat& sum, const EnvBlock& b) {
  Split best;
  double bestScore = -1;
  const double h = b.y1 - b.y0, w = b.x1 - b.x0;
  for (uint32_t x = b.x0 + 1; x < b.x1; ++x) {
    const double l = sum.rect(b.x0, b.y0, x, b.y1), r = b.sum - l;
    const double score = l * l / ((x - b.x0) * h) + r * r / ((b.x1 - x) * h);
    if (score > bestScore) bestScore = score, best = {true, true, x};
  }
  for (uint32_t y = b.y0 + 1; y < b.y1; ++y) {
    const double l = sum.rect(b.x0, b.y0, b.x1, y), r = b.sum - l;
    const double score = l * l / ((y - b.y0) * w) + r * r / ((b.y1 - y) * w);
    if (score > bestScore) bestScore = score, best = {true, false, y};
  }
  return best;
}
}  // namespace

EnvKdTree buildEnvKdTree(const std::vector<double>& w, uint32_t width, uint32_t height, uint32_t blocks) {
  if (width == 0 || height == 0) throw std::invalid_argument("kd-tree: zero-sized environment");
  if (w.size() != size_t(width) * height) throw std::invalid_argument("kd-tree: weight count does not match the size");
  if (blocks == 0) throw std::invalid_argument("kd-tree: --blocks must be at least 1");
  const Sat sum(w, width, height, false), sq(w, width, height, true);
  auto make = [&](uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
    EnvBlock b{x0, y0, x1, y1};
    b.sum = sum.rect(x0, y0, x1, y1);
    // SSE in the form sum(w^2) - sum^2/n; rounding can make it slightly negative: clamp.
    b.sse = std::max(0.0, sq.rect(x0, y0, x1, y1) - b.sum * b.sum / b.texels());
    return b;
  };
  EnvKdTree t;
  t.width = width, t.height = height;
  t.blocks.push_back(make(0, 0, width, height));
  t.total = t.blocks[0].sum;
  // Max-heap of block indices by SSE (ties: the older block first, for a deterministic order).
  auto less = [&](uint32_t a, uint32_t b) {
    const double sa = t.blocks[a].sse, sb = t.blocks[b].sse;
    return sa != sb ? sa < sb : a > b;
  };
  std::priority_queue<uint32_t, std::vector<uint32_t>, decltype(less)> heap(less);
  heap.push(0);
  // A block whose SSE is below this relative to the map's is treated as constant (rounding noise of
  // the SAT differences, not structure).
  const double floorSse = 1e-12 * (sq.rect(0, 0, width, height) + 1e-300);
  while (t.blocks.size() < blocks && !heap.empty()) {
    const uint32_t i = heap.top();
    heap.pop();
    const EnvBlock b = t.blocks[i];
    if (b.sse <= floorSse || b.texels() < 2) continue;
    const Split s = bestSplit(sum, b);
    if (!s.ok) continue;
    const EnvBlock l = s.alongX ? make(b.x0, b.y0, s.pos, b.y1) : make(b.x0, b.y0, b.x1, s.pos);
    const EnvBlock r = s.alongX ? make(s.pos, b.y0, b.x1, b.y1) : make(b.x0, s.pos, b.x1, b.y1);
    t.blocks[i] = l;
    t.blocks.push_back(r);
    heap.push(i);
    heap.push(uint32_t(t.blocks.size() - 1));
  }
  return t;
}

}  // namespace shadetwin

namespace shadetwin {

std::vector<uint32_t> blocksByMean(const EnvKdTree& t) {
  std::vector<uint32_t> order(t.blocks.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return t.blocks[a].sum / t.blocks[a].texels() > t.blocks[b].sum / t.blocks[b].texels();
  });
  return order;
}

double fittedBlockProbability(double alpha, uint32_t n, uint32_t k) {
  return std::log1p(1.0 / (alpha + k)) / std::log1p(n / alpha);
}

double blockFitL1(const std::vector<double>& e, double alpha) {
  const uint32_t n = uint32_t(e.size());
  const double norm = 1.0 / std::log1p(n / alpha);
  double l1 = 0;
  for (uint32_t k = 0; k < n; ++k) l1 += std::fabs(std::log1p(1.0 / (alpha + k)) * norm - e[k]);
  return l1;
}

BlockFit fitBlockAlpha(const std::vector<double>& e) {
  if (e.empty()) throw std::invalid_argument("kd-tree fit: no blocks");
  const double lo = std::log(1e-6), hi = std::log(1e6 * double(e.size()));
  auto f = [&](double s) { return blockFitL1(e, std::exp(s)); };
  // The misfit need not be unimodal in alpha (the e_k are not monotone in rank): a scan first, so the
  // local search starts in the basin of the global minimum at this resolution.
  constexpr int kScan = 256;
  int best = 0;
  double bestF = f(lo);
  for (int i = 1; i < kScan; ++i) {
    const double v = f(lo + (hi - lo) * i / (kScan - 1));
    if (v < bestF) bestF = v, best = i;
  }
  double a = lo + (hi - lo) * std::max(best - 1, 0) / (kScan - 1);
  double b = lo + (hi - lo) * std::min(best + 1, kScan - 1) / (kScan - 1);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int it = 0; it < 80 && b - a > 1e-12; ++it) {
    if (fc <= fd) b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    else a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
  }
  BlockFit r;
  const double s = fc <= fd ? c : d;
  r.alpha = std::exp(s), r.l1 = std::min(fc, fd);
  // The scan point itself may be better than the bracket's interior (a kink at the scan point).
  const double sBest = lo + (hi - lo) * best / (kScan - 1);
  if (bestF < r.l1) r.alpha = std::exp(sBest), r.l1 = bestF;
  return r;
}

}  // namespace shadetwin
