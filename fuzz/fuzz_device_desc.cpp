// libFuzzer target: the device-description parser (model/device_desc.cpp, the files under devices/) on arbitrary text.
#include <exception>
#include <string>

#include "fuzz/fuzz_input.h"
#include "model/device_desc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    shadetwin::model::DeviceDesc d =
        shadetwin::model::parseDeviceDesc(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    (void)d;
  } catch (const std::exception& e) {
    shadetwin::fuzz::rejected(e);
  }
  return 0;
}
