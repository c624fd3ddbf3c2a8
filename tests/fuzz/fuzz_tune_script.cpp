// libFuzzer target: s3d::tune::loadScript (the `s3d tune --script` command file) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/tune/tune_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".txt");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::tune::loadScript(file); });
  return 0;
}
