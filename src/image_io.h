// Image files (EXR, HDR, PNG, ... through OpenImageIO) as float RGBA.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadetwin {

struct ImageRGBA {
  uint32_t width = 0, height = 0;
  std::vector<float> texels;  // RGBA, rows top to bottom
};

struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Loads any OpenImageIO-readable file as float RGBA (missing channels: 0, alpha 1). Throws FileError
/// naming the path and the problem (missing file, unreadable format, zero size); for a file under
/// assets/ the message says how to fetch it.
ImageRGBA loadImageRGBA(const std::string& path);

}  // namespace shadetwin
