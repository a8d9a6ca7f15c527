// tinygltf's and stb_image's implementations, compiled from Debian's headers into the sanitized
// and fuzzing builds, so that JSON parsing and image decoding are instrumented too. The normal
// gis_scene does not use this file: it links Debian's libtinygltf.so and libstb.so instead.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
