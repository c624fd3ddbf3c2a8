// The reference traversal of SceneBvh (what shaders/raycast_visibility.comp computes, in the same order with the
// same arithmetic from raycast_shared.h) and the camera a renderer view casts with.
#include <algorithm>
#include <array>
#include <cmath>

#include "s3d/renderer/scene_bvh.h"

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/renderer_shared.h"

namespace s3d::renderer {

RaycastCamera raycastCamera(const Scene& scene, const ViewMatrices& view, bool reversedZ) {
  RaycastCamera camera;
  const glm::mat4 world = reversedZ ? reversedDepthProjection(view.worldProjection, scene.camera.nearPlane, scene.camera.farPlane)
                                    : view.worldProjection;
  const glm::mat4 firstPerson =
      reversedZ ? reversedDepthProjection(view.firstPersonProjection, scene.firstPerson.nearPlane, scene.firstPerson.farPlane)
                : view.firstPersonProjection;
  camera.worldViewProjection = world * view.worldView;
  camera.firstPersonViewProjection = firstPerson * view.firstPersonView;
  const float split = DeferredRenderer::kFirstPersonDeviceDepthMax;
  camera.worldDepthRange = reversedZ ? glm::vec2(0.0f, 1.0f - split) : glm::vec2(split, 1.0f);
  camera.firstPersonDepthRange = reversedZ ? glm::vec2(1.0f - split, 1.0f) : glm::vec2(0.0f, split);
  camera.clearedDepth = reversedZ ? 0.0f : 1.0f;
  return camera;
}

glm::mat4 clipToLayerOf(const glm::mat4& viewProjection) { return glm::mat4(glm::inverse(glm::dmat4(viewProjection))); }

glm::uvec2 visibilityIdOf(const RaycastHit& hit, glm::uvec2 packing) {
  if (!hit.hit) return glm::uvec2(0);
  if (hit.cutout) return glm::uvec2(S3D_RASTER_SHADED, 0u);
  return gpu::packVisibility(hit.object, hit.triangle, glm::uvec4(0, 0, packing.x, packing.y));
}

gpu::PixelRay pixelRayOf(const RaycastCamera& camera, Layer layer, glm::ivec2 subpixel, glm::uvec2 size) {
  const bool world = layer == Layer::World;
  const glm::mat4& viewProjection = world ? camera.worldViewProjection : camera.firstPersonViewProjection;
  const glm::vec4 screen(float(size.x), float(size.y), 1.0f / float(size.x), 1.0f / float(size.y));
  return gpu::pixelRayOf(clipToLayerOf(viewProjection), viewProjection, screen, subpixel,
                         world ? camera.worldDepthRange : camera.firstPersonDepthRange, nearerOf(camera));
}

float nearerOf(const RaycastCamera& camera) { return camera.clearedDepth > 0.5f ? 1.0f : -1.0f; }

bool CutoutCoverage::covers(std::uint32_t objectIndex, std::uint32_t triangle, glm::vec3 b) const {
  const Object& object = scene_.objects[objectIndex];
  const Material& material = object.material;
  const Mesh& mesh = scene_.meshes[object.mesh];
  glm::vec2 uv(0.0f);
  if (!mesh.texCoords.empty())
    uv = b.x * mesh.texCoords[mesh.indices[3 * triangle]] + b.y * mesh.texCoords[mesh.indices[3 * triangle + 1]] +
         b.z * mesh.texCoords[mesh.indices[3 * triangle + 2]];
  float texelAlpha = 1.0f;
  if (material.baseColorTexture != kNoTexture) {
    const Texture& texture = scene_.textures[std::size_t(material.baseColorTexture)];
    const glm::mat3 t = material.baseColorTransform.matrix();  // packed as the renderer's ObjectConstants packs it
    const glm::vec2 at =
        gpu::transformTexCoord(glm::vec4(t[0][0], t[1][0], t[0][1], t[1][1]), glm::vec2(t[2][0], t[2][1]), uv);
    // surface_texels.glsl's filter, alpha only (never sRGB-encoded).
    glm::vec2 wrapped = at - glm::floor(at);
    if (!std::isfinite(wrapped.x) || !std::isfinite(wrapped.y)) wrapped = glm::vec2(0.0f);
    const glm::ivec2 size(int(texture.width), int(texture.height));
    const glm::vec2 position = wrapped * glm::vec2(size) - 0.5f;
    const glm::vec2 corner = glm::floor(position), weight = position - corner;
    auto alpha = [&](int x, int y) {
      x = ((x % size.x) + size.x) % size.x;
      y = ((y % size.y) + size.y) % size.y;
      return float(texture.rgba[4 * (std::size_t(y) * texture.width + std::size_t(x)) + 3]) / 255.0f;
    };
    const int x0 = int(corner.x), y0 = int(corner.y);
    texelAlpha = glm::mix(glm::mix(alpha(x0, y0), alpha(x0 + 1, y0), weight.x),
                          glm::mix(alpha(x0, y0 + 1), alpha(x0 + 1, y0 + 1), weight.x), weight.y);
  }
  return !gpu::cutOut(material.cutoutAlpha, texelAlpha, material.alphaCutoff);
}

std::uint32_t SceneBvh::closestHit(std::uint32_t root, const gpu::PixelRay& ray, float& bestT, float& bestDepth,
                                   const CutoutCoverage* cutouts) const {
  bestT = S3D_INFINITY;
  bestDepth = S3D_INFINITY;
  float bestKey = S3D_INFINITY;
  std::uint32_t best = S3D_BVH_NO_ROOT;
  if (root == S3D_BVH_NO_ROOT) return best;
  const glm::vec3 inverse = gpu::safeInverse(ray.direction);
  std::array<std::uint32_t, S3D_BVH_MAX_DEPTH> stack{};
  std::array<float, S3D_BVH_MAX_DEPTH> stackEntry{};
  std::uint32_t top = 0;
  std::uint32_t node = root;
  bool visit = gpu::boxEntry(ray.origin, inverse, nodes[root].boundsMin, nodes[root].boundsMax, 1.0f) != S3D_INFINITY;
  while (visit) {
    const gpu::BvhNode& n = nodes[node];
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const gpu::BvhTriangle& tri = triangles[i];
        float t = 0.0f, depth = 0.0f;
        if (gpu::leafHit(ray, tri.v0, tri.v1, tri.v2, tri.flags, t, depth) &&
            (best == S3D_BVH_NO_ROOT || gpu::closerHit(depth * ray.nearer, t, tri.object, tri.triangle, bestKey, bestT,
                                                       triangles[best].object, triangles[best].triangle)) &&
            (cutouts == nullptr || (tri.flags & S3D_BVH_CUTOUT) == 0 ||
             cutouts->covers(tri.object, tri.triangle,
                             gpu::rayBarycentrics(ray.origin, ray.direction, tri.v0, tri.v1, tri.v2)))) {
          bestT = t;
          bestDepth = depth;
          bestKey = depth * ray.nearer;
          best = i;
        }
      }
    } else {
      const float limit = gpu::pruneLimit(bestT);
      const float a = gpu::boxEntry(ray.origin, inverse, nodes[n.first].boundsMin, nodes[n.first].boundsMax, limit);
      const float b = gpu::boxEntry(ray.origin, inverse, nodes[n.first + 1].boundsMin, nodes[n.first + 1].boundsMax, limit);
      if (a != S3D_INFINITY || b != S3D_INFINITY) {
        const bool firstNearer = a <= b;
        node = firstNearer ? n.first : n.first + 1;
        const float farther = firstNearer ? b : a;
        if (farther != S3D_INFINITY) {
          stack[top] = firstNearer ? n.first + 1 : n.first;
          stackEntry[top++] = farther;
        }
        continue;
      }
    }
    visit = false;
    while (top > 0 && !visit) {  // the nearest pending subtree that the best hit so far does not rule out
      --top;
      node = stack[top];
      visit = stackEntry[top] <= gpu::pruneLimit(bestT);
    }
  }
  return best;
}

RaycastHit SceneBvh::castPixel(const RaycastCamera& camera, glm::uvec2 pixel, glm::uvec2 size,
                               const CutoutCoverage* cutouts) const {
  return castSubpixel(camera, glm::ivec2(pixel) * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2, size, cutouts);
}

RaycastHit SceneBvh::castSubpixel(const RaycastCamera& camera, glm::ivec2 subpixel, glm::uvec2 size,
                                  const CutoutCoverage* cutouts) const {
  const std::uint32_t roots[2] = {firstPersonRoot, worldRoot};
  const Layer layers[2] = {Layer::FirstPerson, Layer::World};
  for (int layer = 0; layer < 2; ++layer) {  // the first-person layer is in front of the world wherever it is hit
    if (roots[layer] == S3D_BVH_NO_ROOT) continue;
    float t = 0.0f, depth = 0.0f;
    const std::uint32_t index =
        closestHit(roots[layer], pixelRayOf(camera, layers[layer], subpixel, size), t, depth, cutouts);
    if (index == S3D_BVH_NO_ROOT) continue;
    const gpu::BvhTriangle& tri = triangles[index];
    return {true, tri.object, tri.triangle, cutouts == nullptr && (tri.flags & S3D_BVH_CUTOUT) != 0, depth};
  }
  return {false, 0, 0, false, camera.clearedDepth};
}

}  // namespace s3d::renderer
