#pragma once
// A bounding volume hierarchy of a scene's opaque triangles for the ray-cast visibility pass
// (raycast_visibility.h), built on the CPU with Embree's rtcBuildBVH into s3d's own layout (raycast_shared.h:
// 32-byte binary nodes, 48-byte triangles carrying the renderer's visibility ids), plus the plain C++ traversal
// the GPU pass is held to.
//
// What it holds, per layer (each its own tree in the same arrays, with its own root):
// - the world layer in world space (vertices after the object transform);
// - the first-person layer in camera space (Object::transform), cast with its own projection: its rays go from
//   its near to its far plane through firstPersonViewProjection, and any hit there wins over the world, as the
//   layer's device depth range in front of the world's does in the raster pass.
// Transparent objects (Material::isTransparent) are not in it: they write neither depth nor ids in the raster
// G-buffer pass either (the transparent pass blends them over the lit image later). Alpha cut-outs are in it,
// flagged S3D_BVH_CUTOUT: a cast given their alpha test (CutoutCoverage, RaycastCutouts) goes on through a cut
// texel; without it a pixel whose closest hit is a cut-out gets S3D_RASTER_SHADED instead of an id, for the
// raster path to decide. Textured objects get their real ids (the raster visibility pass writes
// S3D_RASTER_SHADED for them, as it shades them itself; a ray-cast render's G-buffer resolve textures them).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/renderer/view_matrices.h"
#include "s3d/renderer/raycast_shared.h"
#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// What a pixel ray is cast with: both layers' projections as the renderer's G-buffer pass draws them.
struct RaycastCamera {
  glm::mat4 worldViewProjection{1.0f};        // world -> clip
  glm::mat4 firstPersonViewProjection{1.0f};  // camera space -> clip
  glm::vec2 worldDepthRange{0.1f, 1.0f};      // viewport depth ranges (Listing 4.3)
  glm::vec2 firstPersonDepthRange{0.0f, 0.1f};
  float clearedDepth = 1.0f;  // device depth where nothing is hit
  bool operator==(const RaycastCamera&) const = default;
};
// The inverse of a layer's view projection that pixel rays are unprojected with (inverted in double).
glm::mat4 clipToLayerOf(const glm::mat4& viewProjection);
// The ray of one layer through a sample of a width x height image (1 / S3D_SUBPIXEL_UNITS pixel units).
gpu::PixelRay pixelRayOf(const RaycastCamera& camera, Layer layer, glm::ivec2 subpixel, glm::uvec2 size);
// PixelRay::nearer of a camera: 1 when a smaller device depth is nearer, -1 under reversed depth.
float nearerOf(const RaycastCamera& camera);
// The camera of the renderer's view (its reversed-Z option swaps near and far in both projections and mirrors the
// depth ranges, as DeferredRenderer does).
RaycastCamera raycastCamera(const Scene& scene, const ViewMatrices& view, bool reversedZ = false);

// One ray's closest hit.
struct RaycastHit {
  bool hit = false;
  std::uint32_t object = 0, triangle = 0;  // the renderer's ids of the hit triangle
  bool cutout = false;                      // an alpha cut-out: the raster path decides the pixel
  float deviceDepth = 1.0f;  // the raster pass's device depth of the hit; the cleared depth without one
};
// The visibility id a hit writes, packed as the raster pass packs it (gpu::packVisibility): S3D_RASTER_SHADED
// for a cut-out; a miss writes 0 (its cleared depth says it shows nothing, as the G-buffer resolve reads it).
glm::uvec2 visibilityIdOf(const RaycastHit& hit, glm::uvec2 visibilityPacking);

// The alpha test of cut-out objects (Material::alphaCutoff) run on a ray's hit, as the raster pass runs it on its
// fragment: the coverage alpha (cutoutAlpha x the base-colour texel's alpha, bilinear and repeating at level 0,
// after the texture transform) at the hit's perspective-correct texture coordinate. The GPU pass runs the same
// test (raycast_visibility.comp, RaycastCutouts). Keeps a reference to the scene.
class CutoutCoverage {
 public:
  explicit CutoutCoverage(const Scene& scene) : scene_(scene) {}
  // Whether triangle `triangle` of object `object` (a cut-out) covers the point with barycentrics `b`.
  bool covers(std::uint32_t object, std::uint32_t triangle, glm::vec3 b) const;

 private:
  const Scene& scene_;
};

// How a tree is built. SpatialSplits: Embree's high-quality builder, which may split a triangle's reference at a
// node plane (a triangle then sits in several leaves, each leaf's box bounding only its part): fewer boxes
// overlap where triangles are long or large, so rays visit fewer nodes, for about ten times the build
// (docs/RESULTS.md "Ray-cast visibility"). Fast: every triangle once, for trees rebuilt with each pose.
enum class BvhQuality { Fast, SpatialSplits };

struct SceneBvh {
  std::vector<gpu::BvhNode> nodes;
  std::vector<gpu::BvhTriangle> triangles;  // each leaf's contiguous (a split triangle: once in each of its leaves)
  std::uint32_t worldRoot = S3D_BVH_NO_ROOT;
  std::uint32_t firstPersonRoot = S3D_BVH_NO_ROOT;
  std::uint32_t firstPersonFirst = 0;  // triangles[firstPersonFirst..] are the first-person layer's, the rest the world's
  glm::uvec2 visibilityPacking{0, 0};  // gpu::visibilityPacking of the scene (FrameConstants::options z, w)

  // Builds both layers' trees. Throws std::invalid_argument naming the scene and the object for an index past
  // its mesh's vertices or a non-finite vertex position, and std::runtime_error when Embree fails or a tree is
  // deeper than S3D_BVH_MAX_DEPTH.
  static SceneBvh build(const Scene& scene, BvhQuality quality = BvhQuality::SpatialSplits);

  // The reference traversal: the closest hit of render pixel `pixel` of a width x height image (its centre's
  // sample), exactly the GPU pass's rule (raycast_shared.h), first-person layer first.
  // With `cutouts` a cut-out's hit counts where its alpha test keeps it (and is not flagged `cutout`).
  RaycastHit castPixel(const RaycastCamera& camera, glm::uvec2 pixel, glm::uvec2 size,
                       const CutoutCoverage* cutouts = nullptr) const;
  // The same for a sample anywhere in the image, in 1 / S3D_SUBPIXEL_UNITS pixel units.
  RaycastHit castSubpixel(const RaycastCamera& camera, glm::ivec2 subpixel, glm::uvec2 size,
                          const CutoutCoverage* cutouts = nullptr) const;
  // The closest hit of one tree along a pixel ray: its triangle's index in `triangles`, its ray parameter and
  // device depth (S3D_BVH_NO_ROOT and infinities for none).
  std::uint32_t closestHit(std::uint32_t root, const gpu::PixelRay& ray, float& t, float& deviceDepth,
                           const CutoutCoverage* cutouts = nullptr) const;
  // Depth of the deeper tree (1 for a single leaf, 0 for no tree).
  std::uint32_t depth() const;
};

}  // namespace s3d::renderer
