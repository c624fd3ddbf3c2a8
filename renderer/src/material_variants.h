#pragma once
// Which pipeline variant draws an object's material in the passes that write depth: the G-buffer (every bit),
// depth-only passes and shadow maps (the cut-out and double-sided bits). Objects without any of these keep the
// plain pipelines (early depth test, back faces culled).
#include <cstddef>

#include "s3d/renderer/scene.h"

namespace s3d::renderer::detail {

constexpr std::size_t kBaseColorVariant = 1;    // samples a base-colour texture
constexpr std::size_t kNormalMapVariant = 2;    // perturbs its normal with a normal map
constexpr std::size_t kCutoutVariant = 4;       // alpha test with discard (no early depth test)
constexpr std::size_t kDoubleSidedVariant = 8;  // no back-face culling, back faces' normals flipped
constexpr std::size_t kMaterialVariants = 16;

inline std::size_t materialVariant(const Material& material) {
  return (material.baseColorTexture != kNoTexture ? kBaseColorVariant : 0) |
         (material.normalTexture != kNoTexture ? kNormalMapVariant : 0) | (material.isCutout() ? kCutoutVariant : 0) |
         (material.doubleSided ? kDoubleSidedVariant : 0);
}

// The variant of depth-only passes: cut-out and double-sided alone, 0..3 (bit 0 cut-out, bit 1 double-sided).
inline std::size_t depthVariant(const Material& material) {
  return (material.isCutout() ? 1 : 0) | (material.doubleSided ? 2 : 0);
}
constexpr std::size_t kDepthVariants = 4;

}  // namespace s3d::renderer::detail
