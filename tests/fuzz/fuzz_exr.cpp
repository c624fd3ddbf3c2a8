// libFuzzer target: s3d::io::readExr (scanline or tiled EXR to linear color + optional Z) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".exr");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::io::readExr(file); });
  return 0;
}
