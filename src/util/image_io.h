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

/// The most a loaded image may take (decoded RGBA32F plus the file's channels): 8 GiB, a third of this machine's memory.
inline constexpr double kMaxImageBytes = 8.0 * 1024 * 1024 * 1024;
struct ImageHeader {
  uint32_t width = 0, height = 0, channels = 0;
};
/// The size of an image file from its header, without decoding it; the same FileErrors as loadImageRGBA for a missing,
/// unreadable or empty file.
ImageHeader imageHeader(const std::string& path);

/// Loads any OpenImageIO-readable file as float RGBA: channels R, G, B (A, else alpha 1) by name, or one gray channel
/// (or Y) replicated. Throws FileError naming the path and the problem (missing file, unreadable format, zero size,
/// other channel sets, more than kMaxImageBytes); for a file under assets/ the message says how to fetch it.
ImageRGBA loadImageRGBA(const std::string& path);

/// Writes float RGBA as an OpenEXR file (half... no: 32-bit float channels R, G, B, A). The file is
/// written next to its destination and renamed into place, so a failed write never destroys an
/// existing file. Throws FileError naming the path.
void writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& rgba);
/// Tone-maps float RGBA (exposure * x, clamp to [0, 1], sRGB encoding) into an 8-bit PNG; same
/// write-then-rename rule.
void writePngToneMapped(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& rgba,
                        float exposure = 1.0f);

}  // namespace shadetwin
