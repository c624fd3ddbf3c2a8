#pragma once
// Scenes from files: glTF 2.0 (.gltf with its .bin and images, or .glb) through Debian's tinygltf, plus an
// optional scene description NAME.scene.json beside NAME.gltf for what glTF does not carry (sky, ambient,
// exposure, a camera path) or to override its lights and camera.
#include <filesystem>
#include <string>
#include <vector>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// True when `scene` names a scene file (ends in .gltf or .glb, any case) rather than a built-in scene.
bool isSceneFile(const std::string& scene);

// NAME.scene.json beside NAME.gltf / NAME.glb (it need not exist).
std::filesystem::path sceneDescriptionPath(const std::filesystem::path& gltfFile);

// Loads a glTF 2.0 file and, when present, its scene description. Throws std::runtime_error naming the file
// for a missing, unreadable or corrupt file, and std::invalid_argument naming the file and the feature for
// content the renderer cannot draw (a required extension, points or lines, spot lights, alpha cut-outs, ...).
// Material mapping and what is ignored: docs/DESIGN.md, "glTF scenes".
Scene loadGltfScene(const std::filesystem::path& file);

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
