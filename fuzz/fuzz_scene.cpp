// libFuzzer target: the scene parser (scene/scene.cpp) on arbitrary bytes as a scene file, with the checkout's assets
// reachable as "../assets/..." (the meshes and environments the shipped scenes name). A SceneError, MeshError or any
// other std::exception is the expected answer to bad input; a crash, a sanitizer report or a hang is a bug.

#include "fuzz/fuzz_input.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = shadetwin::fuzz::inputFile(data, size, "fuzz.json");
  shadetwin::fuzz::parseOrReject([&] { shadetwin::loadScene(path); });
  return 0;
}
