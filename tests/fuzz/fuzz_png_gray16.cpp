// libFuzzer target: s3d::io::readPngGray16 (16-bit grey PNG depth) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/io/depth_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".png");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::io::readPngGray16(file); });
  return 0;
}
