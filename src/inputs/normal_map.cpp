#include "inputs/normal_map.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "util/image_io.h"

namespace shadetwin {

namespace {

constexpr double kPi = std::numbers::pi;

// Uniform [0, 1) from the generator's 32-bit output (24 bits, exact in float and double).
double uniform01(std::mt19937& r) { return double(r() >> 8) * (1.0 / 16777216.0); }
// Standard normal variate, Box-Muller on two uniforms.
double gaussian(std::mt19937& r) {
  const double u1 = uniform01(r), u2 = uniform01(r);
  return std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * kPi * u2);
}
// d wrapped into [-size/2, size/2): the toroidal difference of two coordinates.
double wrapDiff(double d, double size) { return d - size * std::floor(d / size + 0.5); }

void store(NormalMap& m, size_t i, double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  m.n[3 * i] = float(x / l), m.n[3 * i + 1] = float(y / l), m.n[3 * i + 2] = float(z / l);
}

void flakes(const NormalMapSpec& s, NormalMap& m, std::mt19937& rng) {
  const int c = int(std::max(1u, s.cells));
  const double size = s.size, cell = size / c;
  struct Seed {
    double x, y, n[3];
  };
  std::vector<Seed> seeds(size_t(c) * size_t(c));
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < c; ++i) {
      Seed& sd = seeds[size_t(j) * size_t(c) + size_t(i)];
      sd.x = (i + uniform01(rng)) * cell, sd.y = (j + uniform01(rng)) * cell;
      const double theta = s.spread * std::fabs(gaussian(rng)), phi = 2.0 * kPi * uniform01(rng);
      sd.n[0] = std::sin(theta) * std::cos(phi), sd.n[1] = std::sin(theta) * std::sin(phi), sd.n[2] = std::cos(theta);
    }
  // The nearest seed lies in the 5 x 5 cells around the texel's (a seed two cells away can be
  // nearer than the texel's own cell's, which may be sqrt(2) cells away; three cells away cannot).
  tbb::parallel_for(uint32_t(0), s.size, [&](uint32_t y) {
    for (uint32_t x = 0; x < s.size; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const int ci = std::min(int(px / cell), c - 1), cj = std::min(int(py / cell), c - 1);
      double best = 1e300;
      const Seed* nearest = nullptr;
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
          const int i = ((ci + di) % c + c) % c, j = ((cj + dj) % c + c) % c;
          const Seed& sd = seeds[size_t(j) * size_t(c) + size_t(i)];
          const double dx = wrapDiff(px - sd.x, size), dy = wrapDiff(py - sd.y, size), d2 = dx * dx + dy * dy;
          if (d2 < best) best = d2, nearest = &sd;  // ties: the first in this fixed order
        }
      store(m, size_t(y) * s.size + x, nearest->n[0], nearest->n[1], nearest->n[2]);
    }
  });
}

void scratches(const NormalMapSpec& s, NormalMap& m, std::mt19937& rng) {
  const double size = s.size;
  for (size_t i = 0; i < m.n.size(); i += 3) m.n[i] = 0.0f, m.n[i + 1] = 0.0f, m.n[i + 2] = 1.0f;
  const double st = std::sin(double(s.spread)), ct = std::cos(double(s.spread));
  for (uint32_t k = 0; k < s.count; ++k) {
    const double cx = uniform01(rng) * size, cy = uniform01(rng) * size, a = kPi * uniform01(rng);
    const double len = size * (0.1 + 0.5 * uniform01(rng)), hw = 0.5 * double(s.width);
    const double tx = std::cos(a), ty = std::sin(a), nx = -ty, ny = tx;
    const double ext = 0.5 * len + hw + 1.0;
    const int x0 = int(std::floor(cx - ext)), x1 = int(std::ceil(cx + ext));
    const int y0 = int(std::floor(cy - ext)), y1 = int(std::ceil(cy + ext));
    for (int yy = y0; yy <= y1; ++yy)
      for (int xx = x0; xx <= x1; ++xx) {
        const int x = ((xx % int(s.size)) + int(s.size)) % int(s.size), y = ((yy % int(s.size)) + int(s.size)) % int(s.size);
        const double dx = wrapDiff(x + 0.5 - cx, size), dy = wrapDiff(y + 0.5 - cy, size);
        const double along = dx * tx + dy * ty, across = dx * nx + dy * ny;
        if (std::fabs(along) > 0.5 * len || std::fabs(across) > hw) continue;
        // V-groove: the facet on either side of the centre line faces it.
        const double side = across >= 0.0 ? -1.0 : 1.0;
        store(m, size_t(y) * s.size + size_t(x), side * st * nx, side * st * ny, ct);
      }
  }
}

// A periodic height field: sum of cosine waves with integer frequencies (fx, fy) cycles per map;
// the normals from its analytic slopes, scaled to RMS slope `spread`.
void waves(const NormalMapSpec& s, NormalMap& m, std::mt19937& rng, bool brushed) {
  const int N = int(s.size);
  constexpr int kWaves = 64;
  struct Wave {
    int fx, fy;
    double amp, phase;
  };
  std::vector<Wave> w(kWaves);
  const int lo = std::max(1, N / 64), hi = std::max(lo + 1, brushed ? N / 8 : N / 16);
  for (Wave& v : w) {
    const double f = lo + (hi - lo) * uniform01(rng);
    if (brushed) {
      v.fy = int(std::lround(f));
      v.fx = int(std::lround(4.0 * uniform01(rng))) - 2;  // along the brush: at most 2 cycles
    } else {
      const double a = 2.0 * kPi * uniform01(rng);
      v.fx = int(std::lround(f * std::cos(a))), v.fy = int(std::lround(f * std::sin(a)));
      if (v.fx == 0 && v.fy == 0) v.fx = lo;
    }
    v.amp = 1.0 / std::hypot(double(v.fx), double(v.fy));  // equal slope amplitude per wave
    v.phase = 2.0 * kPi * uniform01(rng);
  }
  // cos(A + B), sin(A + B) from per-column and per-row tables (A = 2 pi fx x / N + phase, B = 2 pi fy y / N).
  std::vector<double> cosX(size_t(kWaves) * N), sinX(size_t(kWaves) * N), cosY(size_t(kWaves) * N), sinY(size_t(kWaves) * N);
  for (int k = 0; k < kWaves; ++k)
    for (int i = 0; i < N; ++i) {
      const double A = 2.0 * kPi * w[size_t(k)].fx * (i + 0.5) / N + w[size_t(k)].phase, B = 2.0 * kPi * w[size_t(k)].fy * (i + 0.5) / N;
      cosX[size_t(k) * N + i] = std::cos(A), sinX[size_t(k) * N + i] = std::sin(A);
      cosY[size_t(k) * N + i] = std::cos(B), sinY[size_t(k) * N + i] = std::sin(B);
    }
  std::vector<double> slope(2 * size_t(N) * N);
  tbb::parallel_for(0, N, [&](int y) {
    for (int x = 0; x < N; ++x) {
      double gx = 0, gy = 0;
      for (int k = 0; k < kWaves; ++k) {
        // d/dx amp cos(A + B) = -amp (2 pi fx / N) sin(A + B)
        const double sAB = sinX[size_t(k) * N + x] * cosY[size_t(k) * N + y] + cosX[size_t(k) * N + x] * sinY[size_t(k) * N + y];
        const double g = -w[size_t(k)].amp * 2.0 * kPi / N * sAB;
        gx += g * w[size_t(k)].fx, gy += g * w[size_t(k)].fy;
      }
      slope[2 * (size_t(y) * N + x)] = gx, slope[2 * (size_t(y) * N + x) + 1] = gy;
    }
  });
  double ms = 0;
  for (size_t i = 0; i < slope.size(); i += 2) ms += slope[i] * slope[i] + slope[i + 1] * slope[i + 1];
  const double scale = double(s.spread) / std::sqrt(ms / (double(N) * N));
  for (size_t i = 0; i < size_t(N) * N; ++i) store(m, i, -scale * slope[2 * i], -scale * slope[2 * i + 1], 1.0);
}

}  // namespace

NormalMapKind normalMapKind(const std::string& name) {
  for (NormalMapKind k : {NormalMapKind::Flat, NormalMapKind::Flakes, NormalMapKind::Scratches, NormalMapKind::Brushed,
                          NormalMapKind::Bumps})
    if (name == normalMapKindName(k)) return k;
  throw std::invalid_argument("unknown normal map '" + name + "' (expected flat, flakes, scratches, brushed or bumps)");
}

const char* normalMapKindName(NormalMapKind k) {
  switch (k) {
    case NormalMapKind::Flat: return "flat";
    case NormalMapKind::Flakes: return "flakes";
    case NormalMapKind::Scratches: return "scratches";
    case NormalMapKind::Brushed: return "brushed";
    case NormalMapKind::Bumps: return "bumps";
  }
  return "?";
}

NormalMap generateNormalMap(const NormalMapSpec& s) {
  if (s.size < 1 || s.size > 8192) throw std::invalid_argument("normal map: size " + std::to_string(s.size) + " outside [1, 8192]");
  if (!(s.spread >= 0.0f) || s.spread > 1.5f) throw std::invalid_argument("normal map: spread must be in [0, 1.5] radians");
  NormalMap m;
  m.width = m.height = s.size;
  m.n.assign(3 * size_t(s.size) * s.size, 0.0f);
  std::mt19937 rng(s.seed);
  switch (s.kind) {
    case NormalMapKind::Flat:
      for (size_t i = 0; i < m.n.size(); i += 3) m.n[i + 2] = 1.0f;
      break;
    case NormalMapKind::Flakes: flakes(s, m, rng); break;
    case NormalMapKind::Scratches: scratches(s, m, rng); break;
    case NormalMapKind::Brushed: waves(s, m, rng, true); break;
    case NormalMapKind::Bumps: waves(s, m, rng, false); break;
  }
  return m;
}

NormalMap loadNormalMap(const std::string& path) {
  const ImageRGBA img = loadImageRGBA(path);  // FileError for missing / unreadable files
  if (auto in = OIIO::ImageInput::open(path); in && in->spec().nchannels < 3)
    throw FileError(path + ": a normal map needs three channels (x, y, z), this file has " + std::to_string(in->spec().nchannels));
  NormalMap m;
  m.width = img.width, m.height = img.height;
  m.n.resize(3 * size_t(img.width) * img.height);
  bool signedValues = false;
  for (size_t i = 0; i < size_t(img.width) * img.height && !signedValues; ++i)
    for (int c = 0; c < 3; ++c) signedValues = signedValues || img.texels[4 * i + size_t(c)] < 0.0f;
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    double v[3];
    for (int c = 0; c < 3; ++c) {
      const double t = img.texels[4 * i + size_t(c)];
      v[c] = signedValues ? t : 2.0 * t - 1.0;
    }
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 1e-6) || !(v[2] > 0.0))
      throw FileError(path + ": texel (" + std::to_string(i % img.width) + ", " + std::to_string(i / img.width) +
                      ") is not a tangent-space normal (" + (l > 1e-6 ? "points below the surface" : "zero length") + ")");
    store(m, i, v[0], v[1], v[2]);
  }
  return m;
}

}  // namespace shadetwin
