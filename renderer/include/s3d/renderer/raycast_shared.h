// The ray-cast visibility pass's data layout and per-ray arithmetic, shared by C++ (SceneBvh's reference
// traversal) and GLSL (shaders/raycast_visibility.comp), so the GPU and its reference cannot drift apart.
#ifndef S3D_RAYCAST_SHARED_H
#define S3D_RAYCAST_SHARED_H

#include "s3d/gpu/shared.h"

#ifdef __cplusplus
namespace s3d::gpu {
using glm::cross;
}
#define S3D_PRECISE
#else
#define S3D_PRECISE precise  // no fused multiply-add: the GPU computes what the C++ reference computes
#endif

S3D_GPU_BEGIN

#define S3D_BVH_NO_ROOT 0xffffffffu  // a layer without triangles
#define S3D_BVH_MAX_DEPTH 64         // the traversal stack's size; the build refuses deeper trees
#define S3D_BVH_DOUBLE_SIDED 1u      // BvhTriangle::flags: drawn without back-face culling
#define S3D_BVH_CUTOUT 2u            // an alpha cut-out: only the raster pass's alpha test decides its pixels
#define S3D_RAYCAST_GROUP_SIZE 8

// A node of the binary BVH (32 bytes, std430): its bounds, then an inner node (count 0) has its two children at
// nodes[first] and nodes[first + 1]; a leaf holds triangles [first, first + count).
struct BvhNode {
  vec3 boundsMin;
  uint first;
  vec3 boundsMax;
  uint count;
};

// A triangle in its layer's space (world, or camera space for the first-person layer) with the renderer's id of
// it: the scene's object index and the triangle's index in its mesh (what the raster visibility pass writes).
struct BvhTriangle {
  vec3 v0;
  uint object;
  vec3 v1;
  uint triangle;
  vec3 v2;
  uint flags;  // S3D_BVH_*
};

// The pass's uniform buffer (std140).
struct RaycastConstants {
  mat4 clipToLayer[2];     // per layer (S3D_LAYER_WORLD, S3D_LAYER_FIRST_PERSON): inverse of viewProjection
  mat4 viewProjection[2];  // layer space -> clip, as the raster pass projects it (device depth of a hit)
  vec4 depthRanges;        // xy: the world layer's viewport depth range, zw: the first-person layer's
  vec4 screen;             // width, height, 1 / width, 1 / height
  uvec4 roots;             // x: the world BVH's root node, y: the first-person BVH's (S3D_BVH_NO_ROOT: none)
  uvec4 options;           // x: mask threshold, y: 1 with a mask, z, w: visibility packing (FrameConstants)
  vec4 clearedDepth;       // x: the device depth of a pixel that shows nothing (sky)
  uvec4 region;            // x: 1 casts only the pixels of the tiles flagged in the region's buffer (the others get
                           // the cleared depth and id 0), y: tiles per row (S3D_TILE_SIZE pixels square)
};

// A point of the pixel ray: the layer-space position of normalized device coordinates (ndc, z); z 0 and 1 give
// the ray's ends on the near and far planes (both depth conventions: the ray is clipped as the raster clips).
// Matrix products are spelled out column by column so both compilers evaluate them in the same order.
S3D_INLINE vec3 unprojectNdc(mat4 clipToLayer, vec2 ndc, float z) {
  S3D_PRECISE vec4 p = clipToLayer[0] * ndc.x + clipToLayer[1] * ndc.y + clipToLayer[2] * z + clipToLayer[3];
  return vec3(p.x, p.y, p.z) / p.w;
}

// The normalized device coordinates of a pixel's centre (screen: width, height, 1 / width, 1 / height).
S3D_INLINE vec2 pixelNdc(uvec2 pixel, vec4 screen) {
  return (vec2(float(pixel.x), float(pixel.y)) + 0.5f) * vec2(screen.z, screen.w) * 2.0f - 1.0f;
}

// 1 / direction with zero components replaced by a tiny value of either sign, so the slab test never computes
// 0 * infinity.
S3D_INLINE vec3 safeInverse(vec3 d) {
  const float tiny = 1e-30f;
  return vec3(1.0f / (abs(d.x) > tiny ? d.x : tiny), 1.0f / (abs(d.y) > tiny ? d.y : tiny),
              1.0f / (abs(d.z) > tiny ? d.z : tiny));
}

// Where the ray origin + t direction enters the box, or infinity when it misses the box within [0, tMax]. The
// exit distance is widened by 3 ulp (PBRT's robust slab test) so a flat box (a ground plane) is never missed by
// rounding where its triangle is hit.
S3D_INLINE float boxEntry(vec3 origin, vec3 inverseDirection, vec3 lo, vec3 hi, float tMax) {
  S3D_PRECISE vec3 t0 = (lo - origin) * inverseDirection;
  S3D_PRECISE vec3 t1 = (hi - origin) * inverseDirection;
  vec3 tNear = min(t0, t1), tFar = max(t0, t1);
  float entry = max(max(tNear.x, tNear.y), max(tNear.z, 0.0f));
  float exit = min(min(tFar.x, tFar.y), min(tFar.z, tMax)) * 1.00000036f;
  return entry <= exit ? entry : S3D_INFINITY;
}

// Möller-Trumbore: the ray parameter t of the hit, or infinity. Edges and vertices count as inside (u, v >= 0,
// u + v <= 1), so a ray through a shared edge hits both triangles at the same t and the tie rule (closerHit)
// picks one. A back face (the vertices clockwise as seen along the ray: det <= 0) is culled unless the triangle
// is double-sided, as the raster pass's counter-clockwise front face does; an edge-on triangle (det 0) never hits.
S3D_INLINE float intersectTriangle(vec3 origin, vec3 direction, vec3 v0, vec3 v1, vec3 v2, uint flags) {
  S3D_PRECISE vec3 e1 = v1 - v0;
  S3D_PRECISE vec3 e2 = v2 - v0;
  S3D_PRECISE vec3 p = cross(direction, e2);
  S3D_PRECISE float det = dot(e1, p);
  if ((flags & S3D_BVH_DOUBLE_SIDED) != 0u ? det == 0.0f : !(det > 0.0f)) return S3D_INFINITY;
  S3D_PRECISE float inverseDet = 1.0f / det;
  S3D_PRECISE vec3 s = origin - v0;
  S3D_PRECISE float u = dot(s, p) * inverseDet;
  if (u < 0.0f || u > 1.0f) return S3D_INFINITY;
  S3D_PRECISE vec3 q = cross(s, e1);
  S3D_PRECISE float v = dot(direction, q) * inverseDet;
  if (v < 0.0f || u + v > 1.0f) return S3D_INFINITY;
  S3D_PRECISE float t = dot(e2, q) * inverseDet;
  return t >= 0.0f ? t : S3D_INFINITY;
}

// The tie rule of the closest hit: the smaller t; at equal t (a shared edge, coplanar overlaps) the lower object
// index, then the lower triangle index, whatever order the traversal meets them in.
S3D_INLINE bool closerHit(float t, uint object, uint triangle, float bestT, uint bestObject, uint bestTriangle) {
  if (t != bestT) return t < bestT;
  return object != bestObject ? object < bestObject : triangle < bestTriangle;
}

// The device depth the raster pass writes for a layer-space point: the viewport maps ndc z into the layer's range.
S3D_INLINE float deviceDepthOf(mat4 viewProjection, vec3 point, vec2 depthRange) {
  S3D_PRECISE vec4 clip = viewProjection[0] * point.x + viewProjection[1] * point.y + viewProjection[2] * point.z +
                         viewProjection[3];
  return depthRange.x + clip.z / clip.w * (depthRange.y - depthRange.x);
}

S3D_GPU_END

#endif  // S3D_RAYCAST_SHARED_H
