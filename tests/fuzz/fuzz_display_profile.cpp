// libFuzzer target: s3d::comfort::loadDisplayProfile (flat-screen or HMD display JSON) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/comfort/display_profile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".json");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::comfort::loadDisplayProfile(file); });
  return 0;
}
