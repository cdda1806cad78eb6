#include "image_io.h"

#include <OpenImageIO/imageio.h>

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

}  // namespace shadetwin
