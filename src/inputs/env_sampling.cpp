#include "inputs/env_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "util/timer.h"

namespace shadetwin {

uint32_t envMethodOf(const std::string& technique) {
  if (technique == "kdtree-mis") return shade::scalar::kEnvKdTree;
  if (technique == "alias-mis") return shade::scalar::kEnvAlias;
  if (technique == "inversion-mis") return shade::scalar::kEnvInversion;
  throw std::invalid_argument("technique '" + technique + "' has no environment sampler");
}

namespace {

std::shared_ptr<const emu::Texture> floatTexture(emu::Format f, uint32_t w, uint32_t h, const std::vector<float>& v) {
  return std::make_shared<emu::Texture>(emu::floatTexture(f, w, h, v.data()));
}

// Walker / Vose alias table of probabilities p (sum 1): q_k and alias_k with
// P(k) = (q_k + sum_{j: alias_j = k} (1 - q_j)) / n.
void aliasTable(const std::vector<double>& p, std::vector<double>& q, std::vector<uint32_t>& alias) {
  const size_t n = p.size();
  q.assign(n, 1.0);
  alias.resize(n);
  std::vector<double> s(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    s[i] = p[i] * double(n);
    alias[i] = uint32_t(i);
    (s[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    const uint32_t l = small.back(), g = large.back();
    small.pop_back();
    q[l] = s[l], alias[l] = g;
    s[g] = (s[g] + s[l]) - 1.0;
    if (s[g] < 1.0) {
      large.pop_back();
      small.push_back(g);
    }
  }
  // Leftovers are 1 up to rounding.
  for (uint32_t i : small) q[i] = 1.0, alias[i] = i;
  for (uint32_t i : large) q[i] = 1.0, alias[i] = i;
}

}  // namespace

EnvSamplingTables envSamplingTables(const emu::Texture& env, uint32_t method, uint32_t blocks) {
  if (env.format() != emu::Format::RGBA32F)
    throw std::invalid_argument("environment sampling: the environment must be RGBA32F");
  EnvSamplingTables T;
  T.buildMs = timeMs([&] {
    const uint32_t W = env.width(), H = env.height();
    std::vector<double> w = envSamplingWeights(reinterpret_cast<const float*>(env.levels()[0].data()), W, H);
    double total = 0;
    for (double v : w) total += v;
    if (!(total > 0))  // nothing to importance-sample: uniform over the sphere (weight sin theta)
      for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) w[size_t(y) * W + x] = std::sin((y + 0.5) * std::numbers::pi / H);
    const double invTwoPi2 = 1.0 / (2 * std::numbers::pi * std::numbers::pi);
    auto& u = T.uniforms;
    u.method = method, u.width = W, u.height = H;
    u.invWidth = 1.0f / float(W), u.invHeight = 1.0f / float(H);
    if (method == shade::scalar::kEnvInversion) {
      std::vector<float> marginal(H), conditional(size_t(W) * H);
      std::vector<double> rowSum(H, 0.0);
      double sum = 0;
      for (uint32_t y = 0; y < H; ++y) {
        for (uint32_t x = 0; x < W; ++x) rowSum[y] += w[size_t(y) * W + x];
        sum += rowSum[y];
      }
      double acc = 0;
      for (uint32_t y = 0; y < H; ++y) {
        acc += rowSum[y];
        marginal[y] = y + 1 == H ? 1.0f : float(acc / sum);
        double c = 0;
        for (uint32_t x = 0; x < W; ++x) {
          c += w[size_t(y) * W + x];
          conditional[size_t(y) * W + x] = x + 1 == W || !(rowSum[y] > 0) ? 1.0f : float(c / rowSum[y]);
        }
        if (!(rowSum[y] > 0))  // never drawn (zero mass): any valid CDF
          for (uint32_t x = 0; x < W; ++x) conditional[size_t(y) * W + x] = 1.0f;
      }
      T.table = floatTexture(emu::Format::R32F, H, 1, marginal);
      T.texels = floatTexture(emu::Format::R32F, W, H, conditional);
      T.samplingBytes = inversionTableBytes(W, H);
      return;
    }
    const EnvKdTree tree = buildEnvKdTree(w, W, H, std::max(1u, blocks));
    const std::vector<uint32_t> order = blocksByMean(tree);
    const uint32_t n = uint32_t(order.size());
    std::vector<double> e(n);
    for (uint32_t k = 0; k < n; ++k) e[k] = tree.blocks[order[k]].sum / tree.total;
    T.fit = fitBlockAlpha(e);
    std::vector<double> q;
    std::vector<uint32_t> alias;
    aliasTable(e, q, alias);
    const uint32_t tw = 2 * std::min(n, 1024u), th = (n + 1023) / 1024;
    std::vector<float> table(size_t(tw) * th * 4, 0.0f), rank(size_t(W) * H);
    for (uint32_t k = 0; k < n; ++k) {
      const EnvBlock& b = tree.blocks[order[k]];
      const double uvScale = double(W) * H / b.texels() * invTwoPi2;
      float* r = &table[(size_t(k / 1024) * tw + 2 * (k % 1024)) * 4];
      r[0] = float(b.x0), r[1] = float(b.y0), r[2] = float(b.x1 - b.x0), r[3] = float(b.y1 - b.y0);
      r[4] = float(fittedBlockProbability(T.fit.alpha, n, k) * uvScale);
      r[5] = float(e[k] * uvScale);
      r[6] = float(q[k]);
      r[7] = float(alias[k]);
      for (uint32_t y = b.y0; y < b.y1; ++y)
        for (uint32_t x = b.x0; x < b.x1; ++x) rank[size_t(y) * W + x] = float(k);
    }
    u.count = n;
    u.alpha = float(T.fit.alpha);
    u.log2Span = float(std::log2(1.0 + n / T.fit.alpha));
    T.table = floatTexture(emu::Format::RGBA32F, tw, th, table);
    T.texels = floatTexture(emu::Format::R32F, W, H, rank);
    // kd-tree: corners + the fitted uv pdf (2 x 16 B per block as stored); alias adds nothing beyond
    // the same record (exact uv pdf, q, alias). The pdf of any direction needs the rank texture.
    T.samplingBytes = size_t(n) * 32;
    T.pdfBytes = size_t(W) * H * 4;
  });
  return T;
}

}  // namespace shadetwin
