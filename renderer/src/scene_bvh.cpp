// SceneBvh: Embree's rtcBuildBVH builds the tree through callbacks into nodes of its thread-local allocator,
// which are then laid out depth first as s3d's 32-byte nodes (siblings adjacent) with each leaf's triangles
// contiguous; plus the reference traversal.
#include "s3d/renderer/scene_bvh.h"

#include "s3d/renderer/renderer_shared.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>

namespace s3d::renderer {
namespace {

// Embree's build nodes (trivially destructible: the allocator frees them with the BVH).
struct BuildNode {
  bool leaf = false;
};
struct BuildInner : BuildNode {
  BuildNode* children[2] = {nullptr, nullptr};
  RTCBounds bounds[2] = {};
};
struct BuildLeaf : BuildNode {
  std::uint32_t count = 0;
  std::uint32_t* primitives = nullptr;  // `count` indices into the layer's triangles
};

void* createNode(RTCThreadLocalAllocator alloc, unsigned int, void*) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16)) BuildInner;
}
void setChildren(void* node, void** children, unsigned int count, void*) {
  for (unsigned int i = 0; i < count && i < 2; ++i) static_cast<BuildInner*>(node)->children[i] = static_cast<BuildNode*>(children[i]);
}
void setBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
  for (unsigned int i = 0; i < count && i < 2; ++i) static_cast<BuildInner*>(node)->bounds[i] = *bounds[i];
}
void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* primitives, size_t count, void*) {
  auto* leaf = new (rtcThreadLocalAlloc(alloc, sizeof(BuildLeaf), 16)) BuildLeaf;
  leaf->leaf = true;
  leaf->count = std::uint32_t(count);
  leaf->primitives = static_cast<std::uint32_t*>(rtcThreadLocalAlloc(alloc, sizeof(std::uint32_t) * std::max<size_t>(count, 1), 4));
  for (std::size_t i = 0; i < count; ++i) leaf->primitives[i] = primitives[i].primID;
  return leaf;
}

// Spatial splits: the part of a triangle's reference on each side of an axis-aligned plane, as the bounds of the
// triangle clipped to that side, within the reference's own bounds (a reference may already be a part).
void splitPrimitive(const RTCBuildPrimitive* primitive, unsigned int dimension, float position, RTCBounds* left,
                    RTCBounds* right, void* userPtr) {
  const auto& source = *static_cast<const std::vector<gpu::BvhTriangle>*>(userPtr);
  const gpu::BvhTriangle& t = source[primitive->primID];
  const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
  glm::vec3 leftLo(INFINITY), leftHi(-INFINITY), rightLo(INFINITY), rightHi(-INFINITY);
  auto add = [](glm::vec3& lo, glm::vec3& hi, glm::vec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 a = v[i], b = v[(i + 1) % 3];
    const float da = a[dimension], db = b[dimension];
    if (da <= position) add(leftLo, leftHi, a);
    if (da >= position) add(rightLo, rightHi, a);
    if ((da < position && db > position) || (da > position && db < position)) {
      glm::vec3 crossing = a + (b - a) * ((position - da) / (db - da));
      crossing[dimension] = position;
      add(leftLo, leftHi, crossing);
      add(rightLo, rightHi, crossing);
    }
  }
  const glm::vec3 lo(primitive->lower_x, primitive->lower_y, primitive->lower_z);
  const glm::vec3 hi(primitive->upper_x, primitive->upper_y, primitive->upper_z);
  leftLo = glm::max(leftLo, lo);
  leftHi = glm::min(leftHi, hi);
  rightLo = glm::max(rightLo, lo);
  rightHi = glm::min(rightHi, hi);
  leftHi[dimension] = std::min(leftHi[dimension], position);
  rightLo[dimension] = std::max(rightLo[dimension], position);
  *left = {leftLo.x, leftLo.y, leftLo.z, 0.0f, leftHi.x, leftHi.y, leftHi.z, 0.0f};
  *right = {rightLo.x, rightLo.y, rightLo.z, 0.0f, rightHi.x, rightHi.y, rightHi.z, 0.0f};
}

struct EmbreeDevice {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCBVH bvh = device ? rtcNewBVH(device) : nullptr;
  EmbreeDevice() = default;
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  ~EmbreeDevice() {
    if (bvh) rtcReleaseBVH(bvh);
    if (device) rtcReleaseDevice(device);
  }
};

glm::vec3 boundsMin(const RTCBounds& b) { return {b.lower_x, b.lower_y, b.lower_z}; }
glm::vec3 boundsMax(const RTCBounds& b) { return {b.upper_x, b.upper_y, b.upper_z}; }

// How far a node's box reaches past its triangles: a leaf decides coverage on vertices snapped to 1/256 pixel, so
// a ray up to 1/512 pixel outside a triangle's own bounds can still hit it (a box edge along a pixel-centre row).
// 1/256 of the box's longest side covers that for triangles down to half a pixel, plus a few ulp of its
// coordinates for flat boxes far from the origin; a parent's margin is never smaller than its children's.
float boundsMargin(glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 extent = hi - lo;
  const glm::vec3 magnitude = glm::max(glm::abs(lo), glm::abs(hi));
  return std::max({extent.x, extent.y, extent.z}) / 256.0f +
         std::max({magnitude.x, magnitude.y, magnitude.z}) / 1048576.0f;
}

// Lays out the subtree of `node` (bounds `bounds`) at nodes[index], moving its triangles from `source` into
// `out` in leaf order.
void flatten(const BuildNode* node, const RTCBounds& bounds, std::uint32_t index, SceneBvh& bvh,
             const std::vector<gpu::BvhTriangle>& source) {
  gpu::BvhNode& out = bvh.nodes[index];
  const float margin = boundsMargin(boundsMin(bounds), boundsMax(bounds));
  out.boundsMin = boundsMin(bounds) - margin;
  out.boundsMax = boundsMax(bounds) + margin;
  if (node->leaf) {
    const auto* leaf = static_cast<const BuildLeaf*>(node);
    bvh.nodes[index].first = std::uint32_t(bvh.triangles.size());
    bvh.nodes[index].count = leaf->count;
    for (std::uint32_t i = 0; i < leaf->count; ++i) bvh.triangles.push_back(source[leaf->primitives[i]]);
    return;
  }
  const auto* inner = static_cast<const BuildInner*>(node);
  const auto children = std::uint32_t(bvh.nodes.size());
  bvh.nodes.resize(bvh.nodes.size() + 2);  // invalidates `out`
  bvh.nodes[index].first = children;
  bvh.nodes[index].count = 0;
  for (std::uint32_t i = 0; i < 2; ++i) flatten(inner->children[i], inner->bounds[i], children + i, bvh, source);
}

// The layer's triangles in its space, in (object, triangle) order.
std::vector<gpu::BvhTriangle> layerTriangles(const Scene& scene, Layer layer) {
  std::vector<gpu::BvhTriangle> triangles;
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    if (object.layer != layer || object.material.isTransparent()) continue;
    const Mesh& mesh = scene.meshes.at(object.mesh);
    const std::uint32_t flags = (object.material.doubleSided ? S3D_BVH_DOUBLE_SIDED : 0u) |
                                (object.material.isCutout() ? S3D_BVH_CUTOUT : 0u);
    auto position = [&](std::uint32_t index) {
      if (index >= mesh.vertices.size())
        throw std::invalid_argument("scene '" + scene.name + "': object " + std::to_string(o) + " has vertex index " +
                                    std::to_string(index) + " past its mesh's " + std::to_string(mesh.vertices.size()) +
                                    " vertices");
      // Summed column by column as geometry.vert's product is, so the leaf test snaps the raster pass's positions.
      const glm::mat4& m = object.transform;
      const glm::vec3 q = mesh.vertices[index].position;
      const glm::vec4 p = m[0] * q.x + m[1] * q.y + m[2] * q.z + m[3];
      const glm::vec3 v = glm::vec3(p) / p.w;
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw std::invalid_argument("scene '" + scene.name + "': object " + std::to_string(o) +
                                    " has a vertex at a non-finite position");
      return v;
    };
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      triangles.push_back({position(mesh.indices[t]), std::uint32_t(o), position(mesh.indices[t + 1]),
                           std::uint32_t(t / 3), position(mesh.indices[t + 2]), flags});
  }
  return triangles;
}

// Builds one layer's tree into the arrays; returns its root (S3D_BVH_NO_ROOT without triangles).
std::uint32_t buildLayer(const std::vector<gpu::BvhTriangle>& source, BvhQuality quality, SceneBvh& bvh) {
  if (source.empty()) return S3D_BVH_NO_ROOT;
  const bool spatialSplits = quality == BvhQuality::SpatialSplits;
  std::vector<RTCBuildPrimitive> primitives(source.size());
  RTCBounds rootBounds{INFINITY, INFINITY, INFINITY, 0.0f, -INFINITY, -INFINITY, -INFINITY, 0.0f};
  for (std::size_t i = 0; i < source.size(); ++i) {
    const gpu::BvhTriangle& t = source[i];
    const glm::vec3 lo = glm::min(glm::min(t.v0, t.v1), t.v2), hi = glm::max(glm::max(t.v0, t.v1), t.v2);
    primitives[i] = {lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, std::uint32_t(i)};
    rootBounds = {std::min(rootBounds.lower_x, lo.x), std::min(rootBounds.lower_y, lo.y), std::min(rootBounds.lower_z, lo.z), 0.0f,
                  std::max(rootBounds.upper_x, hi.x), std::max(rootBounds.upper_y, hi.y), std::max(rootBounds.upper_z, hi.z), 0.0f};
  }
  if (spatialSplits) primitives.resize(2 * source.size());  // room for the split references (Embree's rule)
  EmbreeDevice embree;
  if (!embree.bvh) throw std::runtime_error("Embree could not create a BVH builder");
  RTCBuildArguments arguments = rtcDefaultBuildArguments();
  arguments.buildQuality = spatialSplits ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
  arguments.maxBranchingFactor = 2;
  arguments.maxDepth = S3D_BVH_MAX_DEPTH;
  arguments.minLeafSize = 1;
  arguments.maxLeafSize = 4;
  arguments.traversalCost = 1.0f;
  arguments.intersectionCost = 1.0f;
  arguments.bvh = embree.bvh;
  arguments.primitives = primitives.data();
  arguments.primitiveCount = source.size();
  arguments.primitiveArrayCapacity = primitives.size();
  arguments.splitPrimitive = spatialSplits ? splitPrimitive : nullptr;
  arguments.userPtr = const_cast<std::vector<gpu::BvhTriangle>*>(&source);
  arguments.createNode = createNode;
  arguments.setNodeChildren = setChildren;
  arguments.setNodeBounds = setBounds;
  arguments.createLeaf = createLeaf;
  const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&arguments));
  if (!root || rtcGetDeviceError(embree.device) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree could not build the ray-cast BVH of " + std::to_string(source.size()) + " triangles");
  const auto index = std::uint32_t(bvh.nodes.size());
  bvh.nodes.emplace_back();
  flatten(root, rootBounds, index, bvh, source);
  return index;
}

std::uint32_t treeDepth(const SceneBvh& bvh, std::uint32_t node) {
  if (node == S3D_BVH_NO_ROOT) return 0;
  const gpu::BvhNode& n = bvh.nodes[node];
  if (n.count > 0) return 1;
  return 1 + std::max(treeDepth(bvh, n.first), treeDepth(bvh, n.first + 1));
}

}  // namespace

SceneBvh SceneBvh::build(const Scene& scene, BvhQuality quality) {
  SceneBvh bvh;
  std::uint64_t mostTriangles = 0;
  for (const Mesh& mesh : scene.meshes) mostTriangles = std::max<std::uint64_t>(mostTriangles, mesh.indices.size() / 3);
  bvh.visibilityPacking = gpu::visibilityPacking(scene.objects.size(), mostTriangles);
  const std::vector<gpu::BvhTriangle> world = layerTriangles(scene, Layer::World);
  const std::vector<gpu::BvhTriangle> firstPerson = layerTriangles(scene, Layer::FirstPerson);
  bvh.triangles.reserve(world.size() + firstPerson.size());  // more with spatial splits
  bvh.worldRoot = buildLayer(world, quality, bvh);
  bvh.firstPersonFirst = std::uint32_t(bvh.triangles.size());
  bvh.firstPersonRoot = buildLayer(firstPerson, quality, bvh);
  if (bvh.depth() > S3D_BVH_MAX_DEPTH)
    throw std::runtime_error("scene '" + scene.name + "': its ray-cast BVH is deeper than " +
                             std::to_string(S3D_BVH_MAX_DEPTH) + " levels");
  return bvh;
}

std::uint32_t SceneBvh::depth() const { return std::max(treeDepth(*this, worldRoot), treeDepth(*this, firstPersonRoot)); }

}  // namespace s3d::renderer
