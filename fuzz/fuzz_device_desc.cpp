// libFuzzer target: the device-description parser (model/device_desc.cpp, the files under devices/) on arbitrary text.
#include <string>

#include "fuzz/fuzz_input.h"
#include "model/device_desc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  shadetwin::fuzz::parseOrReject(
      [&] { shadetwin::model::parseDeviceDesc(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json"); });
  return 0;
}
