// ULP heat maps (issue 21 item 4): where two images differ, one panel per channel, the distance in units in the last
// place on a log scale (1 ULP .. 2^32), with a legend, so a triangle edge or a texture seam shows at a glance. Drawn
// with OpenImageIO's ImageBufAlgo; labels in DejaVu Sans (fonts-dejavu-core), written unlabelled without it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace shadetwin {

struct HeatPanel {
  std::string name;                  // channel, e.g. "color.r"
  uint32_t width = 0, height = 0;    // elements per row, rows
  std::vector<uint32_t> ulp;         // width * height: 0 identical, else the ULP distance (kHeatNotANumber: NaN vs
                                     // a number, or a comparison that is not of floats, e.g. coverage)
};
inline constexpr uint32_t kHeatNotANumber = 0xffffffffu;

/// Colour of a distance on the heat map's scale (RGB in 0..1): identical a dark grey, 1 ULP a dark violet rising
/// through red and orange to a pale yellow at 2^31 and beyond, NaN / not-a-float cyan.
void heatColor(uint32_t ulp, float rgb[3]);

/// Writes the panels (a grid of at most 4 a row, each scaled up to at least 160 pixels on its short side) above a
/// legend; returns "" or a warning (no font). Throws on write errors or when no panel has pixels.
std::string writeUlpHeatMap(const std::string& path, const std::string& title, const std::vector<HeatPanel>& panels);

}  // namespace shadetwin
