#include "util/heatmap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "util/output_file.h"

namespace shadetwin {
namespace {
const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
// A magma-like ramp (dark violet -> red -> orange -> pale yellow), evenly spaced in log2(ULP) over 0..32.
const float kRamp[][3] = {{0.23f, 0.06f, 0.43f}, {0.55f, 0.15f, 0.50f}, {0.85f, 0.25f, 0.36f},
                          {0.98f, 0.50f, 0.25f}, {0.99f, 0.78f, 0.40f}, {0.99f, 0.99f, 0.75f}};
constexpr int kMargin = 16, kTitle = 34, kLabel = 38, kLegend = 70;
}  // namespace

void heatColor(uint32_t ulp, float rgb[3]) {
  if (ulp == 0) {
    rgb[0] = rgb[1] = rgb[2] = 0.12f;
    return;
  }
  if (ulp == kHeatNotANumber) {
    rgb[0] = 0.1f, rgb[1] = 0.85f, rgb[2] = 0.95f;
    return;
  }
  const float t = std::min(1.0f, float(std::log2(double(ulp))) / 31.0f) * 5.0f;  // 1 ULP: 0, 2^31: 5
  const int k = std::min(4, int(t));
  const float f = t - float(k);
  for (int c = 0; c < 3; ++c) rgb[c] = kRamp[k][c] * (1 - f) + kRamp[k + 1][c] * f;
}

std::string writeUlpHeatMap(const std::string& path, const std::string& title, const std::vector<HeatPanel>& panels) {
  using namespace OIIO;
  std::vector<const HeatPanel*> ps;
  for (const HeatPanel& p : panels)
    if (p.width && p.height && p.ulp.size() >= size_t(p.width) * p.height) ps.push_back(&p);
  if (ps.empty()) throw std::invalid_argument("heat map " + path + ": no panel with pixels");
  uint32_t maxW = 0, maxH = 0;
  for (const HeatPanel* p : ps) maxW = std::max(maxW, p->width), maxH = std::max(maxH, p->height);
  // One scale for every panel: the short side at least 160 pixels, the long side at most 1024.
  int scale = std::max(1, int(std::ceil(160.0 / std::min(maxW, maxH))));
  scale = std::max(1, std::min(scale, int(1024 / std::max(maxW, maxH))));
  const int cols = int(std::min<size_t>(4, ps.size())), rows = int((ps.size() + size_t(cols) - 1) / size_t(cols));
  const int cellW = std::max(int(maxW) * scale, 220), cellH = int(maxH) * scale + kLabel;
  const int W = std::max(kMargin + cols * (cellW + kMargin), 800), H = kTitle + rows * (cellH + kMargin) + kLegend;
  ImageBuf img(ImageSpec(W, H, 3, TypeDesc::UINT8));
  const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0};
  ImageBufAlgo::fill(img, white);
  bool fontOk = true;
  auto text = [&](int x, int y, const std::string& s, int size) {
    if (fontOk && !ImageBufAlgo::render_text(img, x, y, s, size, kFont, cspan<float>(black, 3))) fontOk = false;
  };
  text(kMargin, 24, title, 18);
  for (size_t k = 0; k < ps.size(); ++k) {
    const HeatPanel& p = *ps[k];
    const int x0 = kMargin + int(k % size_t(cols)) * (cellW + kMargin);
    const int y0 = kTitle + int(k / size_t(cols)) * (cellH + kMargin);
    size_t differ = 0;
    uint32_t worst = 0;
    for (uint32_t u : p.ulp) differ += u != 0, worst = std::max(worst, u);
    text(x0, y0 + 15, p.name, 14);
    text(x0, y0 + 32, std::to_string(differ) + " differ" +
                          (worst == kHeatNotANumber ? ", NaN/not float" : ", max " + std::to_string(worst) + " ULP"), 12);
    std::vector<uint8_t> px(size_t(p.width) * scale * p.height * scale * 3);
    for (uint32_t y = 0; y < p.height * uint32_t(scale); ++y)
      for (uint32_t x = 0; x < p.width * uint32_t(scale); ++x) {
        float c[3];
        heatColor(p.ulp[size_t(y / uint32_t(scale)) * p.width + x / uint32_t(scale)], c);
        for (int i = 0; i < 3; ++i) px[(size_t(y) * p.width * scale + x) * 3 + size_t(i)] = uint8_t(c[i] * 255.0f + 0.5f);
      }
    ImageBuf panel(ImageSpec(int(p.width) * scale, int(p.height) * scale, 3, TypeDesc::UINT8), px.data());
    ImageBufAlgo::paste(img, x0, y0 + kLabel, 0, 0, panel);
  }
  // Legend: the ramp over 1 .. 2^31 ULP with ticks at every fourth power of two, identical and NaN swatches.
  const int ly = H - kLegend + 18, lx = kMargin + 110, lw = std::min(std::max(256, W - lx - 260), 640);
  float grey[3], nan[3];
  heatColor(0, grey);
  heatColor(kHeatNotANumber, nan);
  ImageBufAlgo::render_box(img, kMargin, ly, kMargin + 20, ly + 16, cspan<float>(grey, 3), true);
  text(kMargin + 26, ly + 13, "identical", 13);
  for (int x = 0; x < lw; ++x) {
    float c[3];
    heatColor(uint32_t(std::min(4294967294.0, std::exp2(31.0 * x / (lw - 1)))), c);
    ImageBufAlgo::render_line(img, lx + x, ly, lx + x, ly + 16, cspan<float>(c, 3));
  }
  const char* ticks[] = {"1", "16", "256", "4K", "64K", "1M", "16M", "256M"};
  for (int e = 0; e < 8; ++e) {
    const int x = lx + int(std::lround(double(lw - 1) * 4 * e / 31.0));
    ImageBufAlgo::render_line(img, x, ly + 16, x, ly + 22, cspan<float>(black, 3));
    text(x - 6, ly + 36, ticks[e], 12);
  }
  text(lx + lw + 8, ly + 13, "ULP (log)", 13);
  ImageBufAlgo::render_box(img, lx + lw + 90, ly, lx + lw + 110, ly + 16, cspan<float>(nan, 3), true);
  text(lx + lw + 116, ly + 13, "NaN / not float", 13);
  OutputFile file(path);
  if (!img.write(file.tempPath())) throw std::runtime_error("heat map " + path + ": " + img.geterror());
  file.commit();
  return fontOk ? "" : std::string("no font ") + kFont + ": heat map " + path + " written without labels";
}

}  // namespace shadetwin
