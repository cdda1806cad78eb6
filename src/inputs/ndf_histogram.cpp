#include "inputs/ndf_histogram.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "lanes/instantiate.h"

namespace shadetwin {

namespace {

shade::scalar::NdfBinning sharedBinning(const NdfBinningSpec& b) {
  return {b.rings, b.sectors, float(b.rings) / b.thetaMax, float(b.sectors) / 6.28318548f};
}

void checkBins(const NdfBinningSpec& b) {
  if (b.rings == 0 || b.sectors == 0 || size_t(b.rings) * b.sectors > 65535)
    throw std::invalid_argument("NDF histogram: " + std::to_string(b.rings) + " x " + std::to_string(b.sectors) +
                                " bins (need 1 to 65,535)");
  if (!(b.thetaMax > 0.0f) || b.thetaMax > 3.14159274f)
    throw std::invalid_argument("NDF histogram: thetaMax " + std::to_string(b.thetaMax) + " outside (0, pi]");
}

std::string mib(size_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

}  // namespace

int tileSpans(int64_t a, int64_t b, int64_t n, TileSpan out[3]) {
  const int64_t len = b - a + 1, s = ((a % n) + n) % n, head = std::min(len, n - s);
  int k = 0;
  out[k++] = {s, s + head - 1, 1};
  const int64_t rest = len - head;
  if (rest / n) out[k++] = {0, n - 1, rest / n};
  if (rest % n) out[k++] = {0, rest % n - 1, 1};
  return k;
}

size_t ndfSatFullBytes(uint32_t width, uint32_t height, const NdfBinningSpec& bins) {
  return size_t(width) * height * bins.rings * bins.sectors * sizeof(uint16_t);
}

uint32_t ndfBinOf(const NdfBinningSpec& bins, const float n[3]) {
  return shade::scalar::ndfBin(sharedBinning(bins), shade::V3<float>(n[0], n[1], n[2]));
}

NdfSat buildNdfSat(const NormalMap& map, const NdfBinningSpec& bins, size_t memoryLimit) {
  const auto t0 = std::chrono::steady_clock::now();
  checkBins(bins);
  if (map.width == 0 || map.height == 0 || map.n.size() != 3 * size_t(map.width) * map.height)
    throw std::invalid_argument("NDF histogram: empty or malformed normal map");
  NdfSat sat;
  sat.width = map.width, sat.height = map.height, sat.bins = bins;
  const size_t texels = size_t(map.width) * map.height, nbins = size_t(bins.rings) * bins.sectors;
  // Bin of every texel, then the exact totals and which rings are used.
  std::vector<uint16_t> binOf(texels);
  const auto shared = sharedBinning(bins);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, texels, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) {
      const float* n = &map.n[3 * i];
      binOf[i] = uint16_t(shade::scalar::ndfBin(shared, shade::V3<float>(n[0], n[1], n[2])));
    }
  });
  sat.totals.assign(nbins, 0);
  for (uint16_t b : binOf) ++sat.totals[b];
  sat.slot.assign(bins.rings, -1);
  for (uint32_t t = 0; t < bins.rings; ++t)
    for (uint32_t p = 0; p < bins.sectors; ++p)
      if (sat.totals[size_t(t) * bins.sectors + p]) sat.slot[t] = 0;
  for (uint32_t t = 0; t < bins.rings; ++t)
    if (sat.slot[t] == 0) sat.slot[t] = int32_t(sat.storedRings++);
  const size_t row = size_t(sat.storedRings) * bins.sectors, need = texels * row * sizeof(uint16_t);
  if (memoryLimit == 0) memoryLimit = size_t(sysconf(_SC_AVPHYS_PAGES)) * size_t(sysconf(_SC_PAGESIZE));
  if (need > memoryLimit)
    throw std::length_error("NDF histogram of a " + std::to_string(map.width) + " x " + std::to_string(map.height) +
                            " map with " + std::to_string(sat.storedRings) + " of " + std::to_string(bins.rings) + " x " +
                            std::to_string(bins.sectors) + " bin rings would need " + mib(need) + " (" +
                            std::to_string(need) + " bytes); " + mib(memoryLimit) + " available");
  sat.table.resize(texels * row);
  // Row prefix sums (modulo 2^16), rows in parallel, then the columns: row y adds row y - 1.
  const uint32_t W = map.width, H = map.height, P = bins.sectors;
  tbb::parallel_for(uint32_t(0), H, [&](uint32_t y) {
    std::vector<uint16_t> run(row, 0);
    uint16_t* out = sat.table.data() + size_t(y) * W * row;
    for (uint32_t x = 0; x < W; ++x) {
      const uint16_t b = binOf[size_t(y) * W + x];
      run[size_t(sat.slot[b / P]) * P + b % P] += 1;
      std::copy(run.begin(), run.end(), out + size_t(x) * row);
    }
  });
  for (uint32_t y = 1; y < H; ++y) {
    uint16_t* cur = sat.table.data() + size_t(y) * W * row;
    const uint16_t* prev = cur - size_t(W) * row;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, size_t(W) * row, 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) cur[i] = uint16_t(cur[i] + prev[i]);
    });
  }
  sat.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return sat;
}

void ndfBoxCounts(const NdfSat& sat, int64_t x0, int64_t y0, int64_t x1, int64_t y1, uint32_t* out) {
  if (x1 < x0 || y1 < y0 || (x1 - x0 + 1) * (y1 - y0 + 1) >= 65536)
    throw std::invalid_argument("NDF histogram: box [" + std::to_string(x0) + ", " + std::to_string(x1) + "] x [" +
                                std::to_string(y0) + ", " + std::to_string(y1) + "] is empty or has 65,536 texels or more");
  const uint32_t P = sat.bins.sectors, row = sat.storedRings * P;
  std::vector<uint16_t> acc(row, 0);
  auto S = [&](int64_t x, int64_t y, uint32_t i) -> uint16_t {
    return x < 0 || y < 0 ? 0 : sat.table[(size_t(y) * sat.width + size_t(x)) * row + i];
  };
  TileSpan xs[3], ys[3];
  const int nx = tileSpans(x0, x1, sat.width, xs), ny = tileSpans(y0, y1, sat.height, ys);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const TileSpan &a = xs[i], &b = ys[j];
      const uint16_t m = uint16_t(a.mult * b.mult);
      for (uint32_t k = 0; k < row; ++k) {
        const uint16_t c = uint16_t(S(a.hi, b.hi, k) - S(a.lo - 1, b.hi, k) - S(a.hi, b.lo - 1, k) + S(a.lo - 1, b.lo - 1, k));
        acc[k] = uint16_t(acc[k] + uint16_t(c * m));
      }
    }
  for (uint32_t t = 0; t < sat.bins.rings; ++t)
    for (uint32_t p = 0; p < P; ++p) out[size_t(t) * P + p] = sat.slot[t] < 0 ? 0u : acc[size_t(sat.slot[t]) * P + p];
}

emu::Texture ndfSatTexture(const NdfSat& sat) {
  const uint32_t P = sat.bins.sectors, G = ndfSatGroups(sat.bins), layers = std::max(1u, sat.storedRings);
  const uint32_t tw = sat.width * G;
  std::vector<std::vector<uint8_t>> level(1, std::vector<uint8_t>(size_t(tw) * sat.height * layers * 16, 0));
  uint32_t* out = reinterpret_cast<uint32_t*>(level[0].data());
  const size_t row = size_t(sat.storedRings) * P;
  for (uint32_t r = 0; r < sat.storedRings; ++r)
    for (uint32_t y = 0; y < sat.height; ++y)
      for (uint32_t x = 0; x < sat.width; ++x) {
        const uint16_t* v = &sat.table[(size_t(y) * sat.width + x) * row + size_t(r) * P];
        for (uint32_t p = 0; p < P; ++p) {
          const uint32_t g = p / 8, j = (p % 8) / 2, shift = 16 * (p % 2);
          out[((size_t(r) * sat.height + y) * tw + size_t(x) * G + g) * 4 + j] |= uint32_t(v[p]) << shift;
        }
      }
  return emu::Texture(emu::Format::RGBA32UI, tw, sat.height, layers, std::move(level));
}

}  // namespace shadetwin
