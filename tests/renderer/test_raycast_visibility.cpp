// The ray-cast visibility pass and its BVH (scene_bvh.h, raycast_visibility.h): the tree holds every opaque
// triangle once inside bounds that contain it, the C++ traversal finds what a brute-force search finds, the GPU
// pass computes what the C++ traversal computes, and both agree with the raster G-buffer pass's visibility ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/raycast_visibility.h"
#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/scene_bvh.h"
#include "vulkan_test.h"

namespace s3d {
namespace {

using renderer::RaycastCamera;
using renderer::SceneBvh;

bool contains(const gpu::BvhNode& node, glm::vec3 lo, glm::vec3 hi) {
  return glm::all(glm::lessThanEqual(node.boundsMin, lo)) && glm::all(glm::greaterThanEqual(node.boundsMax, hi));
}
bool touches(const gpu::BvhNode& node, glm::vec3 lo, glm::vec3 hi) {
  return glm::all(glm::lessThanEqual(node.boundsMin, hi)) && glm::all(glm::greaterThanEqual(node.boundsMax, lo));
}

// The fast tree holds every opaque triangle exactly once; the split tree at least once, in no more references
// than the builder's room (twice the triangles), and never twice in one leaf.
TEST(SceneBvh, HoldsEveryOpaqueTriangle) {
  for (const renderer::BvhQuality quality : {renderer::BvhQuality::Fast, renderer::BvhQuality::SpatialSplits})
    for (const std::string& name : renderer::builtInSceneNames()) {
      const renderer::Scene scene = renderer::makeBuiltInScene(name);
      const SceneBvh bvh = SceneBvh::build(scene, quality);
      const bool fast = quality == renderer::BvhQuality::Fast;
      const std::string what = name + (fast ? " (fast)" : " (splits)");
      std::map<std::pair<std::uint32_t, std::uint32_t>, int> seen;
      for (const gpu::BvhTriangle& t : bvh.triangles) ++seen[{t.object, t.triangle}];
      std::size_t expected = 0;
      for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        if (scene.objects[o].material.isTransparent()) continue;  // never in the raster pass's depth or ids either
        const std::uint32_t count = std::uint32_t(scene.meshes[scene.objects[o].mesh].indices.size() / 3);
        for (std::uint32_t t = 0; t < count; ++t) {
          const int references = seen[std::make_pair(o, t)];
          EXPECT_TRUE(fast ? references == 1 : references >= 1) << what << ": object " << o << " triangle " << t;
        }
        expected += count;
      }
      EXPECT_EQ(seen.size(), expected) << what;  // nothing else (no transparent object's triangle)
      if (fast) {
        EXPECT_EQ(bvh.triangles.size(), expected) << what;
      } else if (name == "courtyard") {
        EXPECT_GT(bvh.triangles.size(), expected) << what;  // its walls and ground split
      }
      EXPECT_LE(bvh.triangles.size(), 2 * expected) << what;
      for (const gpu::BvhNode& node : bvh.nodes) {
        std::set<std::pair<std::uint32_t, std::uint32_t>> leaf;
        for (std::uint32_t i = node.first; node.count > 0 && i < node.first + node.count; ++i)
          EXPECT_TRUE(leaf.insert({bvh.triangles[i].object, bvh.triangles[i].triangle}).second) << what;
      }
    }
}

// Every node's box contains its children's. A fast tree's leaf contains its triangles whole; a split tree's leaf
// at least touches each of its triangles' bounds (it bounds only the part of a split triangle on its side).
TEST(SceneBvh, EveryNodeContainsItsChildrenAndTriangles) {
  for (const renderer::BvhQuality quality : {renderer::BvhQuality::Fast, renderer::BvhQuality::SpatialSplits})
    for (const std::string& name : renderer::builtInSceneNames()) {
      const SceneBvh bvh = SceneBvh::build(renderer::makeBuiltInScene(name), quality);
      const bool fast = quality == renderer::BvhQuality::Fast;
      const std::string what = name + (fast ? " (fast)" : " (splits)");
      ASSERT_NE(bvh.worldRoot, S3D_BVH_NO_ROOT) << what;
      std::vector<int> reached(bvh.nodes.size(), 0);
      for (std::uint32_t root : {bvh.worldRoot, bvh.firstPersonRoot}) {
        if (root == S3D_BVH_NO_ROOT) continue;
        std::vector<std::uint32_t> pending{root};
        while (!pending.empty()) {
          const gpu::BvhNode& node = bvh.nodes[pending.back()];
          ++reached[pending.back()];
          pending.pop_back();
          if (node.count == 0) {
            for (std::uint32_t child : {node.first, node.first + 1}) {
              EXPECT_TRUE(contains(node, bvh.nodes[child].boundsMin, bvh.nodes[child].boundsMax)) << what << ": node " << child;
              pending.push_back(child);
            }
            continue;
          }
          for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
            const gpu::BvhTriangle& t = bvh.triangles[i];
            const glm::vec3 lo = glm::min(glm::min(t.v0, t.v1), t.v2), hi = glm::max(glm::max(t.v0, t.v1), t.v2);
            EXPECT_TRUE(fast ? contains(node, lo, hi) : touches(node, lo, hi)) << what << ": triangle " << i;
          }
        }
      }
      for (std::size_t i = 0; i < reached.size(); ++i) EXPECT_EQ(reached[i], 1) << what << ": node " << i << " reached";
      EXPECT_LE(bvh.depth(), std::uint32_t(S3D_BVH_MAX_DEPTH)) << what;
    }
}

// The closest hit over all triangles of the world layer, with the same leaf test and tie rule.
std::uint32_t bruteForce(const renderer::Scene& scene, const SceneBvh& bvh, const gpu::PixelRay& ray) {
  std::uint32_t best = S3D_BVH_NO_ROOT;
  float bestKey = S3D_INFINITY, bestT = S3D_INFINITY;
  for (std::uint32_t i = 0; i < bvh.triangles.size(); ++i) {
    const gpu::BvhTriangle& t = bvh.triangles[i];
    if (scene.objects[t.object].layer != renderer::Layer::World) continue;
    float hit = 0.0f, depth = 0.0f;
    if (gpu::leafHit(ray, t.v0, t.v1, t.v2, t.flags, hit, depth) &&
        (best == S3D_BVH_NO_ROOT || gpu::closerHit(depth * ray.nearer, hit, t.object, t.triangle, bestKey, bestT,
                                                   bvh.triangles[best].object, bvh.triangles[best].triangle))) {
      best = i;
      bestKey = depth * ray.nearer;
      bestT = hit;
    }
  }
  return best;
}

// The tree prunes nothing it should not: 4000 samples of the courtyard at 160x90, at random 1/256-pixel positions
// (so some fall exactly on snapped edges and vertices), find the triangle a search of all finds, in both depth
// conventions.
TEST(SceneBvh, TraversalFindsWhatSearchingEveryTriangleFinds) {
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  const glm::uvec2 size(160, 90);
  auto id = [](const SceneBvh& bvh, std::uint32_t index) {
    if (index == S3D_BVH_NO_ROOT) return std::pair{S3D_BVH_NO_ROOT, S3D_BVH_NO_ROOT};
    return std::pair{bvh.triangles[index].object, bvh.triangles[index].triangle};
  };
  for (const renderer::BvhQuality quality : {renderer::BvhQuality::Fast, renderer::BvhQuality::SpatialSplits}) {
    const SceneBvh bvh = SceneBvh::build(scene, quality);
    const char* tree = quality == renderer::BvhQuality::Fast ? " (fast)" : " (splits)";
    std::mt19937 random(7);
    std::uniform_int_distribution<int> x(0, int(size.x) * S3D_SUBPIXEL_UNITS - 1), y(0, int(size.y) * S3D_SUBPIXEL_UNITS - 1);
    for (const bool reversed : {false, true}) {
      const RaycastCamera camera =
          renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(size.x) / float(size.y)), reversed);
      int hits = 0;
      for (int i = 0; i < 2000; ++i) {
        const gpu::PixelRay ray = renderer::pixelRayOf(camera, renderer::Layer::World, glm::ivec2(x(random), y(random)), size);
        float t = 0.0f, depth = 0.0f;
        const std::uint32_t found = bvh.closestHit(bvh.worldRoot, ray, t, depth);
        ASSERT_EQ(id(bvh, found), id(bvh, bruteForce(scene, bvh, ray))) << "sample " << i << tree << (reversed ? " (reversed depth)" : "");
        hits += found != S3D_BVH_NO_ROOT ? 1 : 0;
      }
      EXPECT_GT(hits, 1000);  // the rays mostly hit something (the courtyard fills most of the view)
    }
  }
}

// A 16x16-pixel view whose layer space is ndc (identity view projection): framebuffer x = 8 (ndc x + 1).
gpu::PixelRay identityRay(glm::ivec2 subpixel) {
  return gpu::pixelRayOf(glm::mat4(1.0f), glm::mat4(1.0f), glm::vec4(16.0f, 16.0f, 1.0f / 16.0f, 1.0f / 16.0f), subpixel,
                         glm::vec2(0.0f, 1.0f), 1.0f);
}
// The layer-space point at framebuffer position `pixels`, depth z.
glm::vec3 atPixel(glm::vec2 pixels, float z = 0.5f) { return glm::vec3(pixels / 8.0f - 1.0f, z); }

int coverage(glm::ivec2 subpixel, glm::vec3 v0, glm::vec3 v1, glm::vec3 v2, std::uint32_t flags = 0) {
  float depth = 0.0f;
  return gpu::rasterCoverage(identityRay(subpixel), v0, v1, v2, flags, depth);
}

// A quad from pixel centre (2.5, 2.5) to (12.5, 12.5) split along its diagonal, which runs through pixel centres:
// every sample of the quad, edges included, belongs to exactly one of its two triangles (the top-left rule), and
// samples on the quad's top and left edges are in it while those on its bottom and right edges are not.
TEST(RasterRule, SharedEdgesAndTheTopLeftRule) {
  const glm::vec3 topLeft = atPixel({2.5f, 2.5f}), topRight = atPixel({12.5f, 2.5f});
  const glm::vec3 bottomLeft = atPixel({2.5f, 12.5f}), bottomRight = atPixel({12.5f, 12.5f});
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const glm::ivec2 sample = glm::ivec2(x, y) * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2;
      // Counter-clockwise on screen (y down), the front faces.
      const int upper = coverage(sample, topLeft, bottomLeft, topRight);
      const int lower = coverage(sample, topRight, bottomLeft, bottomRight);
      const bool inQuad = x >= 2 && x < 12 && y >= 2 && y < 12;
      EXPECT_EQ(upper + lower, inQuad ? 1 : 0) << "pixel " << x << ", " << y;
    }
}

// Back faces (clockwise on screen) are never covered unless double-sided; a triangle of zero snapped area never is.
TEST(RasterRule, BackFacesAndDegenerateTriangles) {
  const glm::ivec2 centre(8 * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2);
  const glm::vec3 a = atPixel({4.0f, 4.0f}), b = atPixel({4.0f, 14.0f}), c = atPixel({14.0f, 4.0f});
  EXPECT_EQ(coverage(centre, a, b, c), 1);
  EXPECT_EQ(coverage(centre, a, c, b), 0);
  EXPECT_EQ(coverage(centre, a, c, b, S3D_BVH_DOUBLE_SIDED), 1);
  // Less than half a sub-pixel unit tall: its vertices snap onto one line.
  EXPECT_EQ(coverage(centre, atPixel({4.0f, 8.5f}), atPixel({13.0f, 8.5f + 0.001f}), atPixel({13.0f, 8.5f}), S3D_BVH_DOUBLE_SIDED), 0);
}

// Depth is interpolated linearly in the framebuffer, and samples beyond the far plane are dropped (the rasterizer
// clips the triangle there) while the rest of the triangle stays covered.
TEST(RasterRule, DepthIsInterpolatedAndTheFarPlaneClips) {
  const glm::vec3 a = atPixel({0.0f, 0.0f}, 0.0f), b = atPixel({0.0f, 16.0f}, 0.0f), c = atPixel({16.0f, 0.0f}, 1.5f);
  float depth = 0.0f;
  const glm::ivec2 near = glm::ivec2(2, 2) * S3D_SUBPIXEL_UNITS;  // framebuffer (2, 2): depth 1.5 * 2 / 16
  ASSERT_EQ(gpu::rasterCoverage(identityRay(near), a, b, c, 0, depth), 1);
  EXPECT_NEAR(depth, 1.5f * 2.0f / 16.0f, 1e-6f);  // float interpolation of exact weights
  const glm::ivec2 far = glm::ivec2(12, 2) * S3D_SUBPIXEL_UNITS;  // depth 1.5 * 12 / 16 > 1
  EXPECT_EQ(gpu::rasterCoverage(identityRay(far), a, b, c, 0, depth), 0);
}

class RaycastVisibilityTest : public test::VulkanTest {
 protected:
  struct Result {
    std::vector<std::uint32_t> ids;
    std::vector<float> depth;
  };
  // Runs the pass on ids and depth images pre-filled with sentinels; `mask`: R32_UINT values (empty: no mask).
  Result cast(const SceneBvh& bvh, const RaycastCamera& camera, std::uint32_t width, std::uint32_t height,
              const std::vector<std::uint32_t>& mask = {},
              renderer::RaycastSearch search = renderer::RaycastSearch::Automatic) {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const std::size_t count = std::size_t(width) * height;
    vk::Image ids = vk::createImage(context(), VK_FORMAT_R32_UINT, width, height, usage);
    vk::Image depth = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, width, height, usage);
    vk::Image maskImage;
    const std::vector<std::uint32_t> idFill(count, kSentinelId);
    const std::vector<float> depthFill(count, kSentinelDepth);
    vk::uploadImage(context(), ids, std::as_bytes(std::span(idFill)), vk::kComputeWrite);
    vk::uploadImage(context(), depth, std::as_bytes(std::span(depthFill)), vk::kComputeWrite);
    renderer::ShadeMask shadeMask;
    if (!mask.empty()) {
      maskImage = vk::createImage(context(), VK_FORMAT_R32_UINT, width, height, usage);
      vk::uploadImage(context(), maskImage, std::as_bytes(std::span(mask)), vk::kComputeWrite);
      shadeMask.image = &maskImage;
    }
    renderer::RaycastVisibility pass(context());
    pass.setBvh(bvh);
    pass.setSearch(search);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      vk::transition(cmd, ids, vk::kComputeWrite, vk::kComputeWrite);  // the uploads before the pass
      vk::transition(cmd, depth, vk::kComputeWrite, vk::kComputeWrite);
      pass.record(cmd, camera, shadeMask, ids, depth);
    });
    Result result{std::vector<std::uint32_t>(count), std::vector<float>(count)};
    std::vector<std::byte> bytes = vk::readbackImage(context(), ids, vk::kComputeWrite);
    std::memcpy(result.ids.data(), bytes.data(), bytes.size());
    bytes = vk::readbackImage(context(), depth, vk::kComputeWrite);
    std::memcpy(result.depth.data(), bytes.data(), bytes.size());
    return result;
  }
  // The share of pixels where the ray cast names the raster pass's triangle, for one scene and size.
  void expectAgreement(const std::string& name, std::uint32_t width, std::uint32_t height, bool reversed);
  static constexpr std::uint32_t kSentinelId = 0xdeadbeefu;
  static constexpr float kSentinelDepth = 42.0f;
};

// Every pixel of every built-in scene (the courtyard with its first-person weapon) at 96x54, in both depth
// conventions, decided by screen bins and by the tree alone: the GPU's id and device depth are the reference
// traversal's. The arithmetic is shared and marked precise (no fused multiply-add but the explicit fma), so ids
// must match exactly; device depth within 1e-6, as Vulkan lets a GPU divide with 2.5 ulp of error.
TEST_F(RaycastVisibilityTest, GpuEqualsTheReferenceTraversal) {
  constexpr std::uint32_t width = 96, height = 54;
  int firstPerson = 0, sky = 0;
  for (const std::string& name : renderer::builtInSceneNames()) {
    const renderer::Scene scene = renderer::makeBuiltInScene(name);
    const SceneBvh bvh = SceneBvh::build(scene);
    for (const bool reversed : {false, true})
      for (const auto search : {renderer::RaycastSearch::Bins, renderer::RaycastSearch::Tree}) {
        const RaycastCamera camera =
            renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(width) / height), reversed);
        const Result gpu = cast(bvh, camera, width, height, {}, search);
        const std::string what = name + (reversed ? " reversed" : "") +
                                 (search == renderer::RaycastSearch::Bins ? " (bins)" : " (tree)");
        for (std::uint32_t y = 0; y < height; ++y)
          for (std::uint32_t x = 0; x < width; ++x) {
            const renderer::RaycastHit hit = bvh.castPixel(camera, {x, y}, {width, height});
            const std::size_t i = std::size_t(y) * width + x;
            ASSERT_EQ(gpu.ids[i], renderer::visibilityIdOf(hit, bvh.visibilityPacking).x)
                << what << ", pixel " << x << ", " << y;
            ASSERT_NEAR(gpu.depth[i], hit.deviceDepth, 1e-6f) << what << ", pixel " << x << ", " << y;
            firstPerson += hit.hit && scene.objects[hit.object].layer == renderer::Layer::FirstPerson ? 1 : 0;
            sky += hit.hit ? 0 : 1;
          }
      }
  }
  EXPECT_GT(firstPerson, 0);  // a weapon's tree was cast
  EXPECT_GT(sky, 0);          // so was a miss
}

// The screen bins' rule (raycast_shared.h): a set-up triangle covers no pixel centre outside its pixel bounds, so
// a bin that lists every triangle whose bounds touch it lists every triangle that can cover its pixels. Checked
// for every triangle of every built-in scene against every pixel of a 48x27 view.
TEST(RaycastBins, ATriangleCoversNoPixelOutsideItsPixelBounds) {
  constexpr std::uint32_t width = 48, height = 27;
  std::size_t covered = 0;
  for (const std::string& name : renderer::builtInSceneNames()) {
    const renderer::Scene scene = renderer::makeBuiltInScene(name);
    const SceneBvh bvh = SceneBvh::build(scene, renderer::BvhQuality::Fast);
    const RaycastCamera camera = renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(width) / height));
    const glm::vec4 screen(float(width), float(height), 1.0f / width, 1.0f / height);
    for (std::size_t t = 0; t < bvh.triangles.size(); ++t) {
      const gpu::BvhTriangle& triangle = bvh.triangles[t];
      const bool firstPerson = t >= bvh.firstPersonFirst;
      const gpu::SnappedTriangle snapped = gpu::setupTriangle(
          firstPerson ? camera.firstPersonViewProjection : camera.worldViewProjection, screen,
          renderer::nearerOf(camera), triangle.v0, triangle.v1, triangle.v2, triangle.flags);
      const glm::ivec4 bounds = gpu::snappedPixelBounds(snapped, screen);
      for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
          float depth = 0.0f;
          const glm::ivec2 sample = glm::ivec2(x, y) * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2;
          if (gpu::coverSample(snapped, sample, depth) == 0) continue;
          ++covered;
          ASSERT_TRUE(int(x) >= bounds.x && int(x) <= bounds.z && int(y) >= bounds.y && int(y) <= bounds.w)
              << name << ": triangle " << t << " covers pixel " << x << ", " << y << " outside its bounds";
        }
    }
  }
  EXPECT_GT(covered, std::size_t(width) * height);  // the scenes fill their views
}

// Automatic search bins a tree of at most S3D_RAYCAST_BIN_AUTO_REFERENCES references per bin of the view (binning
// costs a pass over every triangle, and long lists overflow): the courtyard's tree at 1920x1080 (8,160 bins), not
// in a 64x32 view (8 bins); Bins and Tree hold whatever the size.
TEST_F(RaycastVisibilityTest, AutomaticSearchBinsTreesOfFewReferencesPerBin) {
  const SceneBvh bvh = SceneBvh::build(renderer::makeBuiltInScene("courtyard"));
  ASSERT_GT(bvh.triangles.size(), std::size_t(8 * S3D_RAYCAST_BIN_AUTO_REFERENCES));
  ASSERT_LT(bvh.triangles.size(), std::size_t(8160 * S3D_RAYCAST_BIN_AUTO_REFERENCES));
  renderer::RaycastVisibility pass(context());
  pass.setBvh(bvh);
  EXPECT_TRUE(pass.usesBins(1920, 1080));
  EXPECT_FALSE(pass.usesBins(64, 32));
  pass.setSearch(renderer::RaycastSearch::Bins);
  EXPECT_TRUE(pass.usesBins(64, 32));
  pass.setSearch(renderer::RaycastSearch::Tree);
  EXPECT_FALSE(pass.usesBins(1920, 1080));
}

// A bin listing more triangles than its capacity leaves its pixels to the tree: the fence's chain link in a
// 32x18 view (2x2 bins, thousands of triangles each) still gives the reference traversal's ids and depths.
TEST_F(RaycastVisibilityTest, AnOverfullBinTraversesTheTree) {
  constexpr std::uint32_t width = 32, height = 18;
  const renderer::Scene scene = renderer::makeBuiltInScene("fence");
  const SceneBvh bvh = SceneBvh::build(scene);
  const RaycastCamera camera = renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(width) / height));
  // The world layer's list of each bin, counted as raycast_bin.comp counts it: one bin must overflow.
  const glm::vec4 screen(float(width), float(height), 1.0f / width, 1.0f / height);
  std::map<std::pair<int, int>, std::size_t> listed;
  for (std::size_t t = 0; t < bvh.firstPersonFirst; ++t) {
    const gpu::BvhTriangle& triangle = bvh.triangles[t];
    const glm::ivec4 bounds = gpu::snappedPixelBounds(
        gpu::setupTriangle(camera.worldViewProjection, screen, renderer::nearerOf(camera), triangle.v0, triangle.v1,
                           triangle.v2, triangle.flags),
        screen);
    if (bounds.z < bounds.x || bounds.w < bounds.y) continue;
    for (int y = bounds.y / S3D_RAYCAST_BIN_SIZE; y <= bounds.w / S3D_RAYCAST_BIN_SIZE; ++y)
      for (int x = bounds.x / S3D_RAYCAST_BIN_SIZE; x <= bounds.z / S3D_RAYCAST_BIN_SIZE; ++x) ++listed[{x, y}];
  }
  std::size_t longest = 0;
  for (const auto& [bin, count] : listed) longest = std::max(longest, count);
  ASSERT_GT(longest, std::size_t(S3D_RAYCAST_BIN_CAPACITY));
  const Result gpu = cast(bvh, camera, width, height, {}, renderer::RaycastSearch::Bins);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const renderer::RaycastHit hit = bvh.castPixel(camera, {x, y}, {width, height});
      const std::size_t i = std::size_t(y) * width + x;
      ASSERT_EQ(gpu.ids[i], renderer::visibilityIdOf(hit, bvh.visibilityPacking).x) << "pixel " << x << ", " << y;
      ASSERT_NEAR(gpu.depth[i], hit.deviceDepth, 1e-6f) << "pixel " << x << ", " << y;
    }
}

// An all-zero mask: no pixel is written (the sentinels stay).
TEST_F(RaycastVisibilityTest, AnEmptyMaskWritesNothing) {
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  constexpr std::uint32_t width = 64, height = 40;
  const RaycastCamera camera = renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(width) / height));
  const Result result = cast(SceneBvh::build(scene), camera, width, height, std::vector<std::uint32_t>(width * height, 0));
  for (std::size_t i = 0; i < result.ids.size(); ++i) {
    ASSERT_EQ(result.ids[i], kSentinelId) << "pixel " << i;
    ASSERT_EQ(result.depth[i], kSentinelDepth) << "pixel " << i;
  }
}

// A mask writes its pixels (as the unmasked pass does) and no others.
TEST_F(RaycastVisibilityTest, AMaskWritesExactlyItsPixels) {
  const renderer::Scene scene = renderer::makeBuiltInScene("courtyard");
  constexpr std::uint32_t width = 64, height = 40;
  const SceneBvh bvh = SceneBvh::build(scene);
  const RaycastCamera camera = renderer::raycastCamera(scene, renderer::centerViewMatrices(scene, float(width) / height));
  std::vector<std::uint32_t> mask(width * height);
  std::mt19937 random(3);
  for (std::uint32_t& value : mask) value = random() % 4;  // threshold 1: three quarters of the pixels
  const Result full = cast(bvh, camera, width, height, {}, renderer::RaycastSearch::Tree);
  const Result masked = cast(bvh, camera, width, height, mask, renderer::RaycastSearch::Bins);
  for (std::size_t i = 0; i < mask.size(); ++i) {
    ASSERT_EQ(masked.ids[i], mask[i] >= 1 ? full.ids[i] : kSentinelId) << "pixel " << i;
    ASSERT_EQ(masked.depth[i], mask[i] >= 1 ? full.depth[i] : kSentinelDepth) << "pixel " << i;
  }
}

// Where a pixel's ray and the raster pass name different surfaces, why.
struct Disagreements {
  std::size_t sky = 0;         // one of them sees the sky
  std::size_t rayTested = 0;   // the leaf rule leaves one of the two triangles to the ray test (rasterCoverage -1)
  std::size_t depthTie = 0;    // the rule covers the sample by both, at device depths within 1e-6 of each other
  std::size_t sharedEdge = 0;  // two triangles with a common edge, the sample within a sub-pixel unit of it
  std::size_t other = 0;
  std::size_t total() const { return sky + rayTested + depthTie + sharedEdge + other; }
};

int commonVertices(const gpu::BvhTriangle& a, const gpu::BvhTriangle& b) {
  int common = 0;
  for (glm::vec3 u : {a.v0, a.v1, a.v2})
    for (glm::vec3 v : {b.v0, b.v1, b.v2}) common += u == v ? 1 : 0;
  return common;
}

// Sorts one differing pixel into Disagreements (ids: narrow, as both passes write them).
void classify(const renderer::Scene& scene, const SceneBvh& bvh, const RaycastCamera& camera, glm::uvec2 pixel,
              glm::uvec2 size, std::uint32_t rasterId, std::uint32_t castId, Disagreements& out) {
  const glm::uvec4 packing(0, 0, bvh.visibilityPacking.x, bvh.visibilityPacking.y);
  auto find = [&](std::uint32_t id) -> const gpu::BvhTriangle* {
    const std::uint32_t object = gpu::unpackVisibilityObject(glm::uvec2(id, 0), packing);
    const std::uint32_t triangle = gpu::unpackVisibilityTriangle(glm::uvec2(id, 0), packing);
    for (const gpu::BvhTriangle& t : bvh.triangles)
      if (t.object == object && t.triangle == triangle) return &t;
    return nullptr;
  };
  const gpu::BvhTriangle* a = find(rasterId);
  const gpu::BvhTriangle* b = find(castId);
  if (!a || !b) {
    ++out.other;
    return;
  }
  float depth[2] = {0.0f, 0.0f};
  int coverage[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    const gpu::BvhTriangle& t = i == 0 ? *a : *b;
    const gpu::PixelRay ray = renderer::pixelRayOf(camera, scene.objects[t.object].layer,
                                                   glm::ivec2(pixel) * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2, size);
    coverage[i] = gpu::rasterCoverage(ray, t.v0, t.v1, t.v2, t.flags, depth[i]);
  }
  if (coverage[0] < 0 || coverage[1] < 0) {
    ++out.rayTested;
  } else if (coverage[0] > 0 && coverage[1] > 0 && std::abs(depth[0] - depth[1]) <= 1e-6f) {
    ++out.depthTie;
  } else if (commonVertices(*a, *b) >= 2) {
    ++out.sharedEdge;
  } else {
    ++out.other;
  }
}

// Every built-in scene's centre view at 160x90 and 480x270, every pixel cast (a mask of all pixels): the ray cast
// names the raster visibility pass's triangle (sky: a miss where the raster's linear depth is infinite) on at least
// 99.9 % of the pixels, as both decide a sample by the same rule (snapped vertices, exact edge functions, the
// top-left rule). The rest (measured on lavapipe, docs/RESULTS.md "Ray-cast edge agreement"): depth ties between
// surfaces the depth buffer cannot tell apart, which the raster pass breaks by its draw order (depth-range), and
// samples within a fraction of a sub-pixel unit of a shared edge, where the rasterizer's own vertex arithmetic
// decides otherwise.
TEST_F(RaycastVisibilityTest, AgreesWithTheRasterVisibilityPass) {
  for (const glm::uvec2 size : {glm::uvec2(160, 90), glm::uvec2(480, 270)})
    for (const std::string& name : renderer::builtInSceneNames()) expectAgreement(name, size.x, size.y, false);
}

// The same under reversed depth (GREATER, near at device depth 1), where the rays run from ndc depth 1 to 0.
TEST_F(RaycastVisibilityTest, AgreesWithTheRasterVisibilityPassUnderReversedDepth) {
  for (const std::string& name : renderer::builtInSceneNames()) expectAgreement(name, 160, 90, true);
}

void RaycastVisibilityTest::expectAgreement(const std::string& name, std::uint32_t width, std::uint32_t height,
                                            bool reversed) {
  renderer::RendererOptions options;
  options.gbufferShading = renderer::RendererOptions::GBufferShading::Visibility;
  options.reversedZ = reversed;
  renderer::DeferredRenderer raster(context(), width, height, options);
  const renderer::Scene scene = renderer::makeBuiltInScene(name);
  const renderer::ViewMatrices view = renderer::centerViewMatrices(scene, float(width) / float(height));
  raster.setScene(scene);
  raster.render(view);
  const std::vector<std::uint32_t> rasterIds = raster.readVisibilityIds();
  const DepthImage linear = raster.readLinearDepth();
  ASSERT_EQ(rasterIds.size(), std::size_t(width) * height) << name;
  const SceneBvh bvh = SceneBvh::build(scene);
  const RaycastCamera camera = renderer::raycastCamera(scene, view, reversed);
  const Result cast = this->cast(bvh, camera, width, height);
  Disagreements differ;
  for (std::size_t i = 0; i < rasterIds.size(); ++i) {
    const bool rasterSky = std::isinf(linear.pixels[i]);
    const bool castSky = cast.depth[i] == camera.clearedDepth;
    if (rasterSky ? castSky : (!castSky && cast.ids[i] == rasterIds[i])) continue;
    if (rasterSky || castSky) {
      ++differ.sky;
      continue;
    }
    classify(scene, bvh, camera, {std::uint32_t(i % width), std::uint32_t(i / width)}, {width, height}, rasterIds[i],
             cast.ids[i], differ);
  }
  const double share = 1.0 - double(differ.total()) / double(rasterIds.size());
  std::cout << "[ ray cast ] " << name << " " << width << "x" << height << (reversed ? " reversed" : "") << ": " << differ.total() << " of "
            << rasterIds.size() << " pixels differ (" << differ.sky << " against the sky, " << differ.rayTested
            << " ray-tested, " << differ.depthTie << " depth ties, " << differ.sharedEdge << " shared edges, "
            << differ.other << " other); " << 100.0 * share << " % agree\n";
  EXPECT_GE(share, 0.999) << name << " at " << width << "x" << height << (reversed ? " (reversed depth)" : "");
}

}  // namespace
}  // namespace s3d
