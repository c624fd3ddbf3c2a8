// stb_image's decoder compiled into the PNG fuzzer, so it carries the fuzzer's coverage and the
// sanitizers' checks; these definitions take precedence over the uninstrumented copy in Debian's libstb.so.
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
