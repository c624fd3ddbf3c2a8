// libFuzzer target: s3d::io::readPng (any PNG to RGBA8) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".png");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::io::readPng(file); });
  return 0;
}
