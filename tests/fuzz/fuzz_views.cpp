// libFuzzer target: s3d::comfort::loadViewConfiguration (per-eye views as OpenXR reports them) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/comfort/view_configuration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".json");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::comfort::loadViewConfiguration(file); });
  return 0;
}
