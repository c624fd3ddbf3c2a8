// libFuzzer target: s3d::io::readExrChannel (one named EXR channel (Z) as depth) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/io/depth_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".exr");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::io::readExrChannel(file, "Z"); });
  return 0;
}
