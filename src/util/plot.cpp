#include "util/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "util/output_file.h"

namespace shadetwin {
namespace {
constexpr int kW = 900, kH = 600, kLeft = 90, kRight = 200, kTop = 50, kBottom = 70;
const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
const float kColors[][3] = {{0.85f, 0.15f, 0.1f}, {0.1f, 0.35f, 0.85f}, {0.1f, 0.6f, 0.2f}, {0.6f, 0.2f, 0.7f},
                            {0.9f, 0.55f, 0.0f}, {0.2f, 0.2f, 0.2f}};
}  // namespace

std::string writeLogLogPlot(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& opts) {
  using namespace OIIO;
  double x0 = std::numeric_limits<double>::max(), x1 = 0, y0 = x0, y1 = 0;
  for (const PlotSeries& s : series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]), y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
  if (!(x1 > 0) || !(y1 > 0)) throw std::invalid_argument("plot " + path + ": no positive data");
  const double lx0 = std::floor(std::log10(x0)), lx1 = std::max(lx0 + 1, std::ceil(std::log10(x1)));
  const double ly0 = std::floor(std::log10(y0)), ly1 = std::max(ly0 + 1, std::ceil(std::log10(y1)));
  auto px = [&](double x) { return kLeft + (std::log10(x) - lx0) / (lx1 - lx0) * (kW - kLeft - kRight); };
  auto py = [&](double y) { return kH - kBottom - (std::log10(y) - ly0) / (ly1 - ly0) * (kH - kTop - kBottom); };
  ImageBuf img(ImageSpec(kW, kH, 3, TypeDesc::UINT8));
  const float white[3] = {1, 1, 1}, grid[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0, 0, 0}, gray[3] = {0.5f, 0.5f, 0.5f};
  ImageBufAlgo::fill(img, white);
  bool fontOk = true;
  auto text = [&](int x, int y, const std::string& s, int size, OIIO::cspan<float> c) {
    if (fontOk && !ImageBufAlgo::render_text(img, x, y, s, size, kFont, c)) fontOk = false;
  };
  char buf[64];
  for (double e = lx0; e <= lx1; ++e) {
    for (int m = 1; m < 10 && e + std::log10(m) <= lx1; ++m) {
      const int x = int(px(std::pow(10.0, e) * m));
      ImageBufAlgo::render_line(img, x, kTop, x, kH - kBottom, m == 1 ? gray : grid);
    }
    std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, e));
    text(int(px(std::pow(10.0, e))) - 10, kH - kBottom + 22, buf, 16, black);
  }
  for (double e = ly0; e <= ly1; ++e) {
    for (int m = 1; m < 10 && e + std::log10(m) <= ly1; ++m) {
      const int y = int(py(std::pow(10.0, e) * m));
      ImageBufAlgo::render_line(img, kLeft, y, kW - kRight, y, m == 1 ? gray : grid);
    }
    std::snprintf(buf, sizeof buf, "1e%d", int(e));
    text(8, int(py(std::pow(10.0, e))) + 5, buf, 16, black);
  }
  ImageBufAlgo::render_box(img, kLeft, kTop, kW - kRight, kH - kBottom, black);
  if (opts.inverseSqrtGuide && !series.empty() && !series[0].x.empty()) {
    const double xa = series[0].x.front(), ya = series[0].y.front();
    for (double t = 0; t < 1; t += 0.04) {  // dashed: every other segment
      const double xs = xa * std::pow(x1 / xa, t), xe = xa * std::pow(x1 / xa, t + 0.02);
      const double ys = ya * std::sqrt(xa / xs), ye = ya * std::sqrt(xa / xe);
      if (ye >= std::pow(10.0, ly0))
        ImageBufAlgo::render_line(img, int(px(xs)), int(py(ys)), int(px(xe)), int(py(ye)), gray);
    }
  }
  for (size_t k = 0; k < series.size(); ++k) {
    const OIIO::cspan<float> c(kColors[k % 6], 3);
    const PlotSeries& s = series[k];
    int lastX = -1, lastY = -1;
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!(s.x[i] > 0 && s.y[i] > 0)) continue;
      const int x = int(px(s.x[i])), y = int(py(s.y[i]));
      ImageBufAlgo::render_box(img, x - 3, y - 3, x + 3, y + 3, c, true);
      if (lastX >= 0)
        for (int d = -1; d <= 1; ++d) ImageBufAlgo::render_line(img, lastX, lastY + d, x, y + d, c);
      lastX = x, lastY = y;
    }
    const int ly = kTop + 20 + 26 * int(k);
    ImageBufAlgo::render_box(img, kW - kRight + 15, ly - 8, kW - kRight + 35, ly - 2, c, true);
    text(kW - kRight + 42, ly, s.name, 16, black);
  }
  if (opts.inverseSqrtGuide) text(kW - kRight + 42, kTop + 20 + 26 * int(series.size()), "slope -1/2", 16, gray);
  text(kLeft, kTop - 18, opts.title, 20, black);
  text(kLeft + (kW - kLeft - kRight) / 2 - 60, kH - 15, opts.xLabel, 18, black);
  text(kW - kRight + 15, kH - kBottom - 10, opts.yLabel + " (log)", 16, black);
  OutputFile file(path);
  if (!img.write(file.tempPath())) throw std::runtime_error("plot " + path + ": " + img.geterror());
  file.commit();
  return fontOk ? "" : std::string("no font ") + kFont + ": plot " + path + " written without labels";
}

}  // namespace shadetwin
