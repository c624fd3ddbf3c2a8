#pragma once
// Scenes from files: glTF 2.0 (.gltf with its .bin and images, or .glb) through Debian's tinygltf, plus an
// optional scene description NAME.scene.json beside NAME.gltf for what glTF does not carry (sky, ambient,
// exposure, a camera path) or to override its lights and camera.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// True when `scene` names a scene file (ends in .gltf or .glb, any case) rather than a built-in scene.
bool isSceneFile(const std::string& scene);

// NAME.scene.json beside NAME.gltf / NAME.glb (it need not exist).
std::filesystem::path sceneDescriptionPath(const std::filesystem::path& gltfFile);

// Most memory a scene may take as it is loaded (decoded textures, vertices, indices), counted before each
// allocation as the image readers' limits are (s3d/image_limits.h): a file cannot declare its way past it.
inline constexpr std::uint64_t kMaxSceneBytes = std::uint64_t(4) << 30;

// Loads a glTF 2.0 file and, when present, its scene description. Throws std::runtime_error naming the file
// for a missing, unreadable or corrupt file, and std::invalid_argument naming the file and the feature for
// content the renderer cannot draw (a required extension, points or lines, spot lights, alpha cut-outs, ...),
// for a node hierarchy that is not a tree, a depth range past kMaxDepthRangeRatio, a transform that overflows
// floats, and data past `memoryLimit`. Every file it reads must be a regular file (a FIFO is refused).
// Material mapping and what is ignored: docs/DESIGN.md, "glTF scenes".
Scene loadGltfScene(const std::filesystem::path& file, std::uint64_t memoryLimit = kMaxSceneBytes);

// The files a scene file reads: itself, its scene description when present, and every buffer and image URI
// that is not a data: URI, resolved against the file's folder (whether or not they exist). Empty for a file that
// cannot be parsed (loadGltfScene names the problem). Lets a tool refuse outputs that would overwrite its input.
std::vector<std::filesystem::path> sceneFileInputs(const std::filesystem::path& file);

// A built-in scene by name (makeBuiltInScene) or a scene file (isSceneFile: loadGltfScene).
Scene loadScene(const std::string& scene);

// Metallic-roughness -> this renderer's Blinn-Phong glossiness: roughness r gives the GGX width a = r^2, whose
// Blinn-Phong equivalent exponent is 2 / a^2 - 2 (Walter et al. 2007); glossiness inverts blinnPhongExponent.
float glossinessFromRoughness(float roughness);

}  // namespace s3d::renderer
