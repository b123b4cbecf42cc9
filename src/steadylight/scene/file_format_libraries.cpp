// tinygltf and tinyobjloader compiled here from Debian's headers (each header holds its library's
// implementation behind a macro) rather than linked from Debian's shared libraries, so that the
// sanitizer and fuzz builds (scripts/test.sh --sanitize, scripts/fuzz.sh) instrument the parsers
// that read users' files as well as our code. tinygltf is built without stb_image (the lib's
// TINYGLTF_NO_STB_IMAGE*): images are decoded by image_decoding.cpp. Compiled without warnings,
// as third-party code.
#define TINYGLTF_IMPLEMENTATION
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>
