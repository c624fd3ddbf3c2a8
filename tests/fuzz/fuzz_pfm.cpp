// libFuzzer target: s3d::io::readPfm (PFM (1- or 3-channel portable float map, either byte order)) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/io/depth_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".pfm");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::io::readPfm(file); });
  return 0;
}
