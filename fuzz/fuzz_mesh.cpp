// libFuzzer target: the mesh loaders (scene/mesh.cpp): the first byte picks the format (npm package JSON, glTF or
// binary glTF), the rest is the file. glTF external buffers resolve next to the file (nothing there: a clear error).

#include "fuzz/fuzz_input.h"
#include "scene/mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const names[3] = {"mesh.json", "mesh.gltf", "mesh.glb"};
  const int kind = data[0] % 3;
  const std::string path = shadetwin::fuzz::inputFile(data + 1, size - 1, names[kind]);
  shadetwin::fuzz::parseOrReject([&] { kind == 0 ? shadetwin::loadNpmMesh(path) : shadetwin::loadGltf(path); });
  return 0;
}
