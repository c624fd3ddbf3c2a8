// libFuzzer target: s3d::renderer::loadGltfScene on arbitrary bytes as a .gltf JSON file (buffers as data: URIs),
// the path where the JSON nesting, node graph, accessor and camera checks matter.
#include "fuzz_input.h"
#include "s3d/renderer/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = s3d::fuzz::writeInputFile(data, size, ".gltf");
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::renderer::loadGltfScene(file); });
  return 0;
}
