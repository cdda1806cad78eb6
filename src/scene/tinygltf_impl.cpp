// The one translation unit that compiles tinygltf (header-only, Debian's libtinygltf-dev). Images
// referenced by a glTF are not decoded here (no stb_image): materials come from the scene file.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
