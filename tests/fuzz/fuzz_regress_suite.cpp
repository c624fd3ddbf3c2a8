// libFuzzer target: s3d::app::loadRegressSuite (the `s3d regress` suite JSON) on arbitrary bytes.
#include "fuzz_input.h"
#include "s3d/app/regress_job.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".json");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::app::loadRegressSuite(file); });
  return 0;
}
