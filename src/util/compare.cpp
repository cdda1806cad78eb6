#include "util/compare.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <stdexcept>

namespace shadetwin {

ImageMetrics compareImages(const ImageRGBA& a, const ImageRGBA& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " vs " + std::to_string(b.width) + "x" + std::to_string(b.height));
  return imageMetrics(a.texels, b.texels);
}

ImageMetrics imageMetrics(std::span<const float> a, std::span<const float> b, std::span<const uint8_t> covered) {
  if (a.size() != b.size()) throw std::invalid_argument("image metrics: pixel counts differ");
  ImageMetrics m;
  double se = 0, rel = 0;
  const size_t n = a.size() / 4;
  for (size_t p = 0; p < n; ++p)
    for (int k = 0; k < 3 && (covered.empty() || covered[p]); ++k) {
      const double x = a[4 * p + size_t(k)], y = b[4 * p + size_t(k)];
      if (!std::isfinite(x) || !std::isfinite(y)) {
        ++m.nonFinite;
        continue;
      }
      const double d = x - y;
      se += d * d;
      rel += d * d / (y * y + 0.01);
      m.peak = std::max(m.peak, y);
      ++m.values;
    }
  if (m.values) {
    const double mse = se / double(m.values);
    m.rmse = std::sqrt(mse);
    m.relMse = rel / double(m.values);
    m.psnr = mse > 0 ? 10.0 * std::log10(m.peak * m.peak / mse) : std::numeric_limits<double>::infinity();
  }
  return m;
}

int compareCommand(const std::string& a, const std::string& b, std::ostream& log) {
  const ImageRGBA ia = loadImageRGBA(a), ib = loadImageRGBA(b);
  ImageMetrics m;
  try {
    m = compareImages(ia, ib);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(a + " vs " + b + ": " + e.what());
  }
  log << a << " vs reference " << b << " (" << ia.width << "x" << ia.height << ", " << m.values << " RGB values)\n";
  log << std::setprecision(6) << "RMSE   " << m.rmse << "\nrelMSE " << m.relMse << "\nPSNR   " << std::fixed
      << std::setprecision(2) << m.psnr << " dB (peak " << m.peak << ")\n";
  if (m.nonFinite) log << "non-finite values (not averaged): " << m.nonFinite << "\n";
  return 0;
}

}  // namespace shadetwin
