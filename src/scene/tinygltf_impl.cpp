// The single translation unit that compiles tinygltf. Images are decoded by Penumbra's own callback
// (src/core/image_decode.cpp: libpng, libjpeg-turbo), so tinygltf's stb_image is left out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
