#include "emu/device_profile.h"

#include <cctype>
#include <stdexcept>
#include <string>

namespace emu {

const DeviceProfile& lavapipeProfile() {
  static const DeviceProfile p{
      "lavapipe", true,
      "Mesa 22.3.6 llvmpipe (LLVM 15, 256-bit), measured with `shadetwin verify texture` and ../shared/facts/lavapipe.md",
      /*filterWeightFracBits=*/0, /*lodFractionBits=*/0, /*unorm8FixedPoint=*/true,
      /*computeVectorLanes=*/8, /*fragmentVectorW=*/4, /*fragmentVectorH=*/2, DenormMode::Preserve, DenormMode::Flush,
      // verified with `shadetwin verify raster` on the shipped scenes, scenes/clipped.json included
      // (triangles crossing every clip plane)
      {/*subPixelBits=*/8, /*viewportFma=*/true, /*interpFma=*/true, /*cwSwapsLast=*/true, /*fineDerivatives=*/true,
       DeviceProfile::Raster::Clip::DrawModule, /*clipFromNearer=*/true, /*clipViewportFma=*/false,
       /*verified=*/true},
      DeviceProfile::ImplicitLod::FastLog2PerQuad, /*implicitLodVerified=*/true};  // verify texture --implicit-lod
  return p;
}

const DeviceProfile& nvidiaProfile() {
  static const DeviceProfile p{
      "nvidia", false,
      "public documentation only (CUDA programming guide, texture fetching: 9-bit weights with 8 fraction bits); "
      "not yet measured on a GPU",
      /*filterWeightFracBits=*/8, /*lodFractionBits=*/8, /*unorm8FixedPoint=*/false,
      /*computeVectorLanes=*/1, /*fragmentVectorW=*/1, /*fragmentVectorH=*/1, DenormMode::Preserve, DenormMode::Preserve,
      {/*subPixelBits=*/8, /*viewportFma=*/true, /*interpFma=*/true, /*cwSwapsLast=*/true, /*fineDerivatives=*/true,
       DeviceProfile::Raster::Clip::GuardBand, /*clipFromNearer=*/false, /*clipViewportFma=*/true,
       /*verified=*/false},
      DeviceProfile::ImplicitLod::Exact, /*implicitLodVerified=*/false};
  return p;
}

const DeviceProfile& profileByName(std::string_view name) {
  if (name == "lavapipe" || name == "llvmpipe") return lavapipeProfile();
  if (name == "nvidia") return nvidiaProfile();
  throw std::invalid_argument("unknown device profile '" + std::string(name) + "' (known: lavapipe, nvidia)");
}

const DeviceProfile& profileForDevice(std::string_view deviceName) {
  std::string n(deviceName);
  for (auto& c : n) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (n.find("nvidia") != std::string::npos) return nvidiaProfile();
  if (n.find("llvmpipe") != std::string::npos) return lavapipeProfile();
  throw std::invalid_argument("no device profile for Vulkan device '" + std::string(deviceName) + "'");
}

}  // namespace emu
