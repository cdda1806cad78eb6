// Error metrics between an image and a reference (`shadetwin compare A B`, B the reference), over
// the R, G, B channels of every pixel:
//   RMSE   = sqrt(mean((a - b)^2))
//   relMSE = mean((a - b)^2 / (b^2 + 0.01))          (Rousselle et al. 2011: eps keeps dark pixels finite)
//   PSNR   = 10 log10(peak^2 / mean((a - b)^2)) dB, peak = the largest R, G or B value of the reference
//            (HDR images have no fixed white; +inf when the images are identical).
// Values that are not finite in either image are not averaged; they are counted and reported.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <ostream>
#include <string>

#include "util/image_io.h"

namespace shadetwin {

struct ImageMetrics {
  double rmse = 0, relMse = 0, psnr = 0, peak = 0;
  size_t values = 0, nonFinite = 0;
};

/// Throws std::invalid_argument naming both sizes when they differ.
ImageMetrics compareImages(const ImageRGBA& a, const ImageRGBA& reference);
/// The same metrics over RGBA float pixels of equal count; with `covered` (one flag per pixel) only
/// the flagged pixels count (e.g. the pixels a G-buffer covers).
ImageMetrics imageMetrics(std::span<const float> a, std::span<const float> reference,
                          std::span<const uint8_t> covered = {});
int compareCommand(const std::string& a, const std::string& b, std::ostream& log);

}  // namespace shadetwin
