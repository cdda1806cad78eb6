#include "util/image_io.h"

#include "util/output_file.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

namespace shadetwin {

namespace {
// OpenEXR 3.1 (Debian's, under OpenImageIO) allocates each header attribute's value at the size the header claims
// before it reads the value: a 1 KiB file that claims a 1.2 GiB string costs that much memory and, under a sanitizer,
// seconds to free (fuzz_image found one; fuzz/regressions/image/exr_attribute_size_past_end). So an EXR's headers are
// walked first, and an attribute that claims more bytes than the file has left is an error naming it. The layout
// (OpenEXR's "File Layout" document): magic 76 2f 31 01, a 4-byte version whose bit 10 allows names of 255 bytes (31
// otherwise) and bit 12 marks a multi-part file; then each header is attributes (name NUL, type NUL, int32 size,
// value) ended by an empty name, and a multi-part file's headers are ended by an empty header.
void checkExrHeaders(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char head[8];
  if (!f.read(reinterpret_cast<char*>(head), 8)) return;  // too short to be an EXR: OpenImageIO says what it is
  static constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  if (std::memcmp(head, kMagic, 4) != 0) return;
  const uint32_t flags = uint32_t(head[5]) << 8 | uint32_t(head[6]) << 16 | uint32_t(head[7]) << 24;
  const size_t maxName = flags & 0x400u ? 255 : 31;
  const bool multipart = (flags & 0x1000u) != 0;
  f.seekg(0, std::ios::end);
  const int64_t fileSize = int64_t(f.tellg());
  f.seekg(8);
  auto readString = [&](const char* what) {
    std::string s;
    for (int c; (c = f.get()) != 0;) {
      if (c == EOF) throw FileError(path + ": EXR header ends inside an attribute's " + std::string(what));
      if (s.size() == maxName) throw FileError(path + ": EXR attribute " + what + " longer than " + std::to_string(maxName) + " bytes");
      s.push_back(char(c));
    }
    return s;
  };
  for (;;) {
    int attributes = 0;
    for (;; ++attributes) {
      const std::string name = readString("name");
      if (name.empty()) break;
      const std::string type = readString("type");
      unsigned char sz[4];
      if (!f.read(reinterpret_cast<char*>(sz), 4)) throw FileError(path + ": EXR header ends inside attribute " + name);
      const int32_t size = int32_t(uint32_t(sz[0]) | uint32_t(sz[1]) << 8 | uint32_t(sz[2]) << 16 | uint32_t(sz[3]) << 24);
      const int64_t left = fileSize - int64_t(f.tellg());
      if (size < 0 || size > left)
        throw FileError(path + ": EXR attribute " + name + " (" + type + ") claims " + std::to_string(size) +
                        " bytes, the file has " + std::to_string(left) + " left");
      f.seekg(size, std::ios::cur);
    }
    if (!multipart || attributes == 0) return;  // a single header, or the empty header that ends a multi-part file's
  }
}

// The file opened for reading, its header checked (present, readable, not empty).
std::unique_ptr<OIIO::ImageInput> openImage(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) {
    std::string hint = path.find("assets/") != std::string::npos ? " (run scripts/setup.sh to fetch the assets)" : "";
    throw FileError(path + ": file not found" + hint);
  }
  checkExrHeaders(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw FileError(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw FileError(path + ": image has zero size (" + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", " +
                    std::to_string(spec.nchannels) + " channels)");
  return in;
}
}  // namespace

ImageHeader imageHeader(const std::string& path) {
  const auto in = openImage(path);
  return {uint32_t(in->spec().width), uint32_t(in->spec().height), uint32_t(in->spec().nchannels)};
}

ImageRGBA loadImageRGBA(const std::string& path) {
  auto in = openImage(path);
  const OIIO::ImageSpec& spec = in->spec();
  // Decoded as float RGBA (and the file's channels once more while decoding): refuse what this machine cannot hold
  // before allocating it, with the memory it would need.
  const double need = double(spec.width) * spec.height * (16.0 + 4.0 * spec.nchannels);
  if (need > kMaxImageBytes)
    throw FileError(path + ": image " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " would need " +
                    std::to_string(int(need / double(1 << 20))) + " MiB to load (limit " + std::to_string(int(kMaxImageBytes / double(1 << 20))) +
                    " MiB)");
  // Channels by name (OpenImageIO's names: R, G, B, A; Y for luminance): RGB(A) as they are; one channel (any name) or Y
  // (with A) as gray; anything else is an error naming the channels found.
  const int nc = spec.nchannels;
  auto channel = [&](const char* name) {
    for (int c = 0; c < nc; ++c)
      if (spec.channelnames.size() > size_t(c) && spec.channelnames[size_t(c)] == name) return c;
    return -1;
  };
  int src[4] = {channel("R"), channel("G"), channel("B"), channel("A")};
  if (src[0] < 0 || src[1] < 0 || src[2] < 0) {
    const int y = nc == 1 ? 0 : channel("Y");
    if (y < 0) {
      std::string names;
      for (int c = 0; c < nc; ++c) names += (c ? ", " : "") + (size_t(c) < spec.channelnames.size() ? spec.channelnames[size_t(c)] : "?");
      throw FileError(path + ": " + std::to_string(nc) + " channels (" + names +
                      "): expected R, G, B (optionally A) or a single gray channel");
    }
    src[0] = src[1] = src[2] = y;
  }
  std::vector<float> raw(size_t(spec.width) * spec.height * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
    throw FileError(path + ": cannot decode pixels: " + in->geterror());
  ImageRGBA img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.texels.resize(size_t(img.width) * img.height * 4);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    const float* p = &raw[i * size_t(nc)];
    float* o = &img.texels[i * 4];
    for (int c = 0; c < 3; ++c) o[c] = p[src[c]];
    o[3] = src[3] >= 0 ? p[src[3]] : 1.0f;
  }
  return img;
}

namespace {

void writeImage(const std::string& path, uint32_t width, uint32_t height, int channels, OIIO::TypeDesc type,
                const void* data) {
  OutputFile file(path);  // a temporary in the same folder, renamed into place when complete
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw FileError(path + ": cannot write: no image writer for this file extension");
  OIIO::ImageSpec spec(int(width), int(height), channels, type);
  // OpenImageIO stamps an EXR with the time it was written (capDate) unless DateTime is given: an empty one keeps two
  // runs' files byte-identical (tests/output_determinism_test.sh), as a CI twin's outputs should be.
  if (type == OIIO::TypeDesc::FLOAT) spec.attribute("DateTime", "");
  if (!out->open(file.tempPath(), spec) || !out->write_image(type, data) || !out->close())
    throw FileError(path + ": cannot write: " + out->geterror());
  file.commit();
}

}  // namespace

void writeExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& rgba) {
  if (rgba.size() != size_t(width) * height * 4) throw FileError(path + ": image size does not match its pixels");
  writeImage(path, width, height, 4, OIIO::TypeDesc::FLOAT, rgba.data());
}

void writePngToneMapped(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& rgba,
                        float exposure) {
  if (rgba.size() != size_t(width) * height * 4) throw FileError(path + ": image size does not match its pixels");
  std::vector<uint8_t> px(size_t(width) * height * 3);
  for (size_t i = 0; i < size_t(width) * height; ++i)
    for (int c = 0; c < 3; ++c) {
      float x = rgba[4 * i + size_t(c)] * exposure;
      x = std::isfinite(x) ? std::fmin(std::fmax(x, 0.0f), 1.0f) : (x > 0 ? 1.0f : 0.0f);
      float s = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
      px[3 * i + size_t(c)] = uint8_t(std::lround(s * 255.0f));
    }
  writeImage(path, width, height, 3, OIIO::TypeDesc::UINT8, px.data());
}

}  // namespace shadetwin
