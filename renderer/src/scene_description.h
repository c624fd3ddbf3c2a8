#pragma once
// NAME.scene.json: what glTF does not carry (sky, ambient, exposure, a camera path) or overrides of its lights
// and camera (scene_file.h).
#include <filesystem>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// What a description replaced of the glTF file's own scene.
struct DescribedParts {
  bool camera = false;  // camera or cameraPath
  bool sun = false;
};

// Applies the description in `file` to `scene`. Throws std::invalid_argument naming the file and the key.
DescribedParts applySceneDescription(const std::filesystem::path& file, Scene& scene);

}  // namespace s3d::renderer
