// libFuzzer target: the image loader (util/image_io.cpp: OpenImageIO, then the project's own checks) on arbitrary bytes;
// the first byte picks the file name's extension (OpenImageIO chooses a reader by it, then by the file's magic).

#include "fuzz/fuzz_input.h"
#include "util/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const names[3] = {"image.exr", "image.hdr", "image.png"};
  const std::string path = shadetwin::fuzz::inputFile(data + 1, size - 1, names[data[0] % 3]);
  shadetwin::fuzz::parseOrReject([&] { shadetwin::loadImageRGBA(path); });
  return 0;
}
