// libFuzzer target: a scene description (NAME.scene.json) on arbitrary bytes, beside a valid one-triangle glTF.
#include "fuzz_input.h"
#include "s3d/renderer/scene_file.h"

namespace {
constexpr const char* kTriangle =
    R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path scene = [] {
    const auto bytes = reinterpret_cast<const std::uint8_t*>(kTriangle);
    const std::filesystem::path written = s3d::fuzz::writeInputFile(bytes, std::strlen(kTriangle), ".gltf");
    std::filesystem::path renamed = written;
    renamed.replace_filename("s3d_fuzz_description_" + std::to_string(::getpid()) + ".gltf");
    std::filesystem::rename(written, renamed);
    return renamed;
  }();
  std::ofstream(s3d::renderer::sceneDescriptionPath(scene), std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  s3d::fuzz::loadExpectingOnlyClearErrors([&] { s3d::renderer::loadGltfScene(scene); });
  return 0;
}
