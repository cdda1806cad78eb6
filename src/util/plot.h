// Log-log line plots as PNG (the sweep's figures), drawn with OpenImageIO's ImageBufAlgo: decade
// grid, one coloured polyline with markers per series, legend, optional N^-1/2 guide. Labels use
// DejaVu Sans (Debian fonts-dejavu-core); without the font the plot is written unlabelled and
// the returned warning says so.
#pragma once
#include <string>
#include <vector>

namespace shadetwin {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // positive values (log axes); others are skipped
};

struct PlotOptions {
  std::string title, xLabel, yLabel;
  bool inverseSqrtGuide = false;  // dashed line of slope -1/2 through the first point of series 0
};

/// Writes the plot; returns "" or a warning (e.g. no font for the labels). Throws on write errors.
std::string writeLogLogPlot(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& opts);

}  // namespace shadetwin
