#include "util/image_io.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>

namespace shadetwin {

ImageRGBA loadImageRGBA(const std::string& path) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) {
    std::string hint = path.find("assets/") != std::string::npos ? " (run scripts/setup.sh to fetch the assets)" : "";
    throw FileError(path + ": file not found" + hint);
  }
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw FileError(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw FileError(path + ": image has zero size");
  const int nc = spec.nchannels;
  std::vector<float> raw(size_t(spec.width) * spec.height * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
    throw FileError(path + ": cannot decode pixels: " + in->geterror());
  ImageRGBA img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.texels.resize(size_t(img.width) * img.height * 4);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    const float* p = &raw[i * nc];
    float* o = &img.texels[i * 4];
    o[0] = p[0];
    o[1] = nc > 1 ? p[1] : (nc == 1 ? p[0] : 0.0f);
    o[2] = nc > 2 ? p[2] : (nc == 1 ? p[0] : 0.0f);
    o[3] = nc > 3 ? p[3] : 1.0f;
  }
  return img;
}

namespace {

void writeImage(const std::string& path, uint32_t width, uint32_t height, int channels, OIIO::TypeDesc type,
                const void* data) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) throw FileError(path + ": cannot write: directory " + dir.string() + " does not exist");
  const fs::path tmp = dir / (".tmp-" + target.filename().string());
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw FileError(path + ": cannot write: no image writer for this file extension");
  OIIO::ImageSpec spec(int(width), int(height), channels, type);
  if (!out->open(tmp.string(), spec) || !out->write_image(type, data) || !out->close()) {
    std::string err = out->geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw FileError(path + ": cannot write: " + err);
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) throw FileError(path + ": cannot write: " + ec.message());
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
