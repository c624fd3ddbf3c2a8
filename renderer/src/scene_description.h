#pragma once
// NAME.scene.json: what glTF does not carry (sky, ambient, exposure, a camera path) or overrides of its lights
// and camera (scene_file.h).
#include <filesystem>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// Applies the description in `file` to `scene`. Throws std::invalid_argument naming the file and the key.
void applySceneDescription(const std::filesystem::path& file, Scene& scene);

}  // namespace s3d::renderer
