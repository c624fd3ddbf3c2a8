#version 450
// Ray-cast visibility: per pixel of the mask, the closest opaque triangle along the pixel-centre ray through a
// BVH of the scene (SceneBvh), each leaf's triangles decided as the rasterizer decides the pixel's sample
// (raycast_shared.h's leafHit: snapped vertices, exact edge functions, the top-left rule), written as the raster
// G-buffer pass writes it: the visibility id (narrow ids, R32_UINT) and the device depth (a miss: the cleared
// depth). The first-person layer's tree is cast first with its own projection; a hit there wins, as its depth
// range in front of the world's does in the raster pass. Pixels outside the mask are not written, or with an
// uncast depth (constants.region.z) get its depth and id 0 (outside a region: the cleared depth). Cut-outs' hits
// run their alpha test with kCutoutAlphaTest (else they write S3D_RASTER_SHADED). The per-ray
// arithmetic is raycast_shared.h's, which the C++ reference traversal (SceneBvh::castPixel) runs in the same order.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "s3d/renderer/raycast_shared.h"

layout(local_size_x = S3D_RAYCAST_GROUP_SIZE, local_size_y = S3D_RAYCAST_GROUP_SIZE) in;
layout(binding = 0) uniform Constants { RaycastConstants constants; };
layout(std430, binding = 1) readonly buffer Nodes { BvhNode nodes[]; };
layout(std430, binding = 2) readonly buffer Triangles { BvhTriangle triangles[]; };
layout(binding = 3, r32ui) uniform readonly uimage2D mask;
layout(binding = 4, r32ui) uniform writeonly uimage2D visibilityIds;
layout(binding = 5, r32f) uniform writeonly image2D deviceDepth;
// With constants.region.x: one flag per tile, nonzero for the tiles to cast (a renderer's tile lists: the ambient
// occlusion's region, whose first tileCount words are exactly those flags).
layout(std430, binding = 6) readonly buffer Region {
  TileHeader regionHeader;
  uint regionFlags[];
};
// Every triangle set up for this view by raycast_setup.comp.
layout(std430, binding = 7) readonly buffer Snapped { SnappedTriangle snapped[]; };
// With constants.region.z: the device depth of the pixels not cast (a hybrid's: its base displacement's depth).
layout(binding = 8, r32f) uniform readonly image2D uncastDepth;
// With kCutoutAlphaTest: what cut-outs' alpha test reads (RaycastCutouts).
layout(constant_id = 0) const bool kCutoutAlphaTest = false;
layout(std430, binding = 9) readonly buffer Objects { ObjectConstants objects[]; };
layout(std430, binding = 10) readonly buffer Indices { uint indices[]; };
// With constants.bins.z: each screen bin's triangle count and list (raycast_bin.comp).
layout(std430, binding = 14) readonly buffer BinCounts { uint binCounts[]; };
layout(std430, binding = 15) readonly buffer BinEntries { uint binEntries[]; };
#define S3D_SURFACE_VERTICES_BINDING 11
#include "surface_vertices.glsl"
#define S3D_TEXTURE_TABLE_BINDING 12
#define S3D_TEXELS_BINDING 13
#include "surface_texels.glsl"

// CutoutCoverage::covers for the ray's hit on tree triangle i: the coverage alpha at its perspective-correct
// texture coordinate.
bool coversCutout(uint i, PixelRay ray) {
  uint objectIndex = triangles[i].object;
  vec3 b = rayBarycentrics(ray.origin, ray.direction, triangles[i].v0, triangles[i].v1, triangles[i].v2);
  uint first = objects[objectIndex].firstIndex + 3u * triangles[i].triangle;
  uvec3 v = uvec3(indices[first], indices[first + 1u], indices[first + 2u]) + objects[objectIndex].vertexOffset;
  vec2 uv = b.x * vertexTexCoord(v.x) + b.y * vertexTexCoord(v.y) + b.z * vertexTexCoord(v.z);
  uint baseColor = objects[objectIndex].surfaceTextures.x;
  float texelAlpha = 1.0;
  if (baseColor != S3D_NO_TEXTURE)
    texelAlpha = sampleTexels(baseColor, transformTexCoord(objects[objectIndex].baseColorUv,
                                                            objects[objectIndex].uvOffsets.xy, uv)).a;
  return !cutOut(objects[objectIndex].albedo.a, texelAlpha, objects[objectIndex].emissive.a);
}

// Tree triangle i's hit made the best so far where it is closer (closerHit) and its alpha test keeps it.
void considerTriangle(uint i, PixelRay ray, inout uint best, inout float bestT, inout float bestDepth,
                      inout float bestKey) {
  float t, depth;
  if (leafHitSetUp(ray, snapped[i], triangles[i].v0, triangles[i].v1, triangles[i].v2, triangles[i].flags, t, depth) &&
      (best == S3D_BVH_NO_ROOT || closerHit(depth * ray.nearer, t, triangles[i].object, triangles[i].triangle, bestKey,
                                            bestT, triangles[best].object, triangles[best].triangle)) &&
      (!kCutoutAlphaTest || (triangles[i].flags & S3D_BVH_CUTOUT) == 0u || coversCutout(i, ray))) {
    bestT = t;
    bestDepth = depth;
    bestKey = depth * ray.nearer;
    best = i;
  }
}

// The closest hit among the `count` triangles a bin lists from binEntries[first]: what the tree's traversal
// finds, as every triangle that may cover the bin's pixels is listed.
uint closestListed(uint first, uint count, PixelRay ray, out float bestT, out float bestDepth) {
  bestT = S3D_INFINITY;
  bestDepth = S3D_INFINITY;
  float bestKey = S3D_INFINITY;
  uint best = S3D_BVH_NO_ROOT;
  for (uint k = first; k < first + count; ++k) considerTriangle(binEntries[k], ray, best, bestT, bestDepth, bestKey);
  return best;
}

// The closest hit of one tree along the pixel ray: its triangle index (S3D_BVH_NO_ROOT: none), ray parameter and
// device depth.
uint closestHit(uint root, PixelRay ray, out float bestT, out float bestDepth) {
  bestT = S3D_INFINITY;
  bestDepth = S3D_INFINITY;
  float bestKey = S3D_INFINITY;
  uint best = S3D_BVH_NO_ROOT;
  if (root == S3D_BVH_NO_ROOT) return best;
  vec3 inverseDirection = safeInverse(ray.direction);
  uint stack[S3D_BVH_MAX_DEPTH];
  float stackEntry[S3D_BVH_MAX_DEPTH];
  uint top = 0u;
  uint node = root;
  bool visit = boxEntry(ray.origin, inverseDirection, nodes[root].boundsMin, nodes[root].boundsMax, 1.0) != S3D_INFINITY;
  while (visit) {
    uint first = nodes[node].first, count = nodes[node].count;
    if (count > 0u) {
      for (uint i = first; i < first + count; ++i) considerTriangle(i, ray, best, bestT, bestDepth, bestKey);
    } else {
      float limit = pruneLimit(bestT);
      float a = boxEntry(ray.origin, inverseDirection, nodes[first].boundsMin, nodes[first].boundsMax, limit);
      float b = boxEntry(ray.origin, inverseDirection, nodes[first + 1u].boundsMin, nodes[first + 1u].boundsMax, limit);
      if (a != S3D_INFINITY || b != S3D_INFINITY) {
        bool firstNearer = a <= b;
        node = firstNearer ? first : first + 1u;
        float farther = firstNearer ? b : a;
        if (farther != S3D_INFINITY) {
          stack[top] = firstNearer ? first + 1u : first;
          stackEntry[top] = farther;
          ++top;
        }
        continue;
      }
    }
    visit = false;
    while (top > 0u && !visit) {  // the nearest pending subtree that the best hit so far does not rule out
      --top;
      node = stack[top];
      visit = stackEntry[top] <= pruneLimit(bestT);
    }
  }
  return best;
}

// The pixel's closest hit in one layer's tree, written; false: the layer has no tree or the ray misses it.
bool castLayer(int layer, uvec2 pixel, ivec2 subpixel) {
  uint root = layer == S3D_LAYER_WORLD ? constants.roots.x : constants.roots.y;
  if (root == S3D_BVH_NO_ROOT) return false;
  vec2 range = layer == S3D_LAYER_WORLD ? constants.depthRanges.xy : constants.depthRanges.zw;
  PixelRay ray = pixelRayOf(constants.clipToLayer[layer], constants.viewProjection[layer], constants.screen, subpixel,
                            range, constants.clearedDepth.y);
  float t, depth;
  uint hit;
  uint bin = (layer == S3D_LAYER_WORLD ? 0u : constants.bins.y) + (pixel.y / S3D_RAYCAST_BIN_SIZE) * constants.bins.x +
             pixel.x / S3D_RAYCAST_BIN_SIZE;
  uint listed = constants.bins.z != 0u ? binCounts[bin] : S3D_RAYCAST_BIN_CAPACITY + 1u;
  if (listed <= S3D_RAYCAST_BIN_CAPACITY)
    hit = closestListed(bin * S3D_RAYCAST_BIN_CAPACITY, listed, ray, t, depth);
  else
    hit = closestHit(root, ray, t, depth);
  if (hit == S3D_BVH_NO_ROOT) return false;
  uvec2 id = !kCutoutAlphaTest && (triangles[hit].flags & S3D_BVH_CUTOUT) != 0u
                 ? uvec2(S3D_RASTER_SHADED, 0u)
                 : packVisibility(triangles[hit].object, triangles[hit].triangle, constants.options);
  imageStore(visibilityIds, ivec2(pixel), uvec4(id.x, 0u, 0u, 0u));
  imageStore(deviceDepth, ivec2(pixel), vec4(depth));
  return true;
}

// The invocation's pixel of its workgroup's bin: each 32 invocations (a GPU's SIMD group) an 8x4 block, a compact
// patch of the mask's clusters rather than two rows of the bin (measured faster: docs/RESULTS.md).
uvec2 pixelOfInvocation() {
  const uint blocksPerRow = S3D_RAYCAST_GROUP_SIZE / 8u;
  uint block = gl_LocalInvocationIndex / 32u, lane = gl_LocalInvocationIndex % 32u;
  uvec2 blockOrigin = uvec2(block % blocksPerRow, block / blocksPerRow) * uvec2(8u, 4u);
  return gl_WorkGroupID.xy * S3D_RAYCAST_GROUP_SIZE + blockOrigin + uvec2(lane % 8u, lane / 8u);
}

void main() {
  uvec2 pixel = pixelOfInvocation();
  if (any(greaterThanEqual(pixel, uvec2(constants.screen.xy)))) return;
  bool masked = constants.options.y == 0u || imageLoad(mask, ivec2(pixel)).r >= constants.options.x;
  if (!masked && constants.region.z == 0u) return;
  if (constants.region.x != 0u &&
      regionFlags[(pixel.y / S3D_TILE_SIZE) * constants.region.y + pixel.x / S3D_TILE_SIZE] == 0u) {
    imageStore(visibilityIds, ivec2(pixel), uvec4(0u));
    imageStore(deviceDepth, ivec2(pixel), vec4(constants.clearedDepth.x));
    return;
  }
  if (!masked) {  // a surface for the ambient occlusion to sample, which nothing shades (the resolve skips it)
    imageStore(visibilityIds, ivec2(pixel), uvec4(0u));
    imageStore(deviceDepth, ivec2(pixel), imageLoad(uncastDepth, ivec2(pixel)));
    return;
  }
  ivec2 subpixel = ivec2(pixel) * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2;  // the pixel's centre
  // The first-person layer, then the world; each call with its layer as a constant, so the layer's matrices are
  // read where they are used rather than held through the traversal.
  if (castLayer(S3D_LAYER_FIRST_PERSON, pixel, subpixel) || castLayer(S3D_LAYER_WORLD, pixel, subpixel)) return;
  imageStore(visibilityIds, ivec2(pixel), uvec4(0u));
  imageStore(deviceDepth, ivec2(pixel), vec4(constants.clearedDepth.x));
}
