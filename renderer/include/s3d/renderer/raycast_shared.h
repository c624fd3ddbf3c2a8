// The ray-cast visibility pass's data layout and per-ray arithmetic, shared by C++ (SceneBvh's reference
// traversal) and GLSL (shaders/raycast_visibility.comp), so the GPU and its reference cannot drift apart.
#ifndef S3D_RAYCAST_SHARED_H
#define S3D_RAYCAST_SHARED_H

#include "s3d/gpu/shared.h"

#ifdef __cplusplus
#include <cmath>

#include <glm/integer.hpp>
namespace s3d::gpu {
using glm::cross;
using glm::imulExtended;
inline float fma(float a, float b, float c) { return std::fma(a, b, c); }  // fused, as GLSL's precise fma
using glm::ivec2;
using glm::ivec4;
using glm::roundEven;
}
#define S3D_PRECISE
#define S3D_OUT(type) type&
#else
#define S3D_PRECISE precise  // no fused multiply-add: the GPU computes what the C++ reference computes
#define S3D_OUT(type) out type
#endif

S3D_GPU_BEGIN

#define S3D_BVH_NO_ROOT 0xffffffffu  // a layer without triangles
#define S3D_BVH_MAX_DEPTH 64         // the traversal stack's size; the build refuses deeper trees
#define S3D_BVH_DOUBLE_SIDED 1u      // BvhTriangle::flags: drawn without back-face culling
#define S3D_BVH_CUTOUT 2u            // an alpha cut-out: only the raster pass's alpha test decides its pixels
// The rasterizer's vertex snapping: VkPhysicalDeviceLimits::subPixelPrecisionBits of the devices s3d runs on
// (lavapipe and the desktop GPUs report 8), so positions are multiples of 1/256 pixel.
#define S3D_SUBPIXEL_BITS 8
#define S3D_SUBPIXEL_UNITS (1 << S3D_SUBPIXEL_BITS)
// Vertices farther than this from the viewport's origin (pixels) are left to the ray test: the rasterizer clips
// such triangles at its guard band, and snapped coordinates relative to a sample must stay within 30 bits so
// their products fit 64.
#define S3D_RASTER_REACH 1048576.0f

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
  vec4 clearedDepth;       // x: the device depth of a pixel that shows nothing (sky), y: PixelRay::nearer
  uvec4 region;            // x: 1 casts only the pixels of the tiles flagged in the region's buffer (the others get
                           // the cleared depth and id 0), y: tiles per row (S3D_TILE_SIZE pixels square), z: 1 gives
                           // the unmasked pixels (of the region, if any) the uncast depth image's depth and id 0
  uvec4 bins;              // x: bins per row, y: bins per layer (S3D_RAYCAST_BIN_SIZE pixels square), z: 1 decides
                           // a pixel by its bin's triangle list where that list is complete; w: 0
};

// Screen bins: each bin lists the set-up triangles of each layer whose snapped bounds hold one of its pixel
// centres (raycast_bin.comp), so a pixel of a complete list is decided by testing that list alone, the same
// leaf test in a loop every pixel of the bin shares, instead of a traversal whose length and path differ from
// ray to ray. A list longer than its capacity is incomplete: its pixels traverse the tree.
#define S3D_RAYCAST_BIN_SIZE 16
// The cast's workgroup is one bin: its pixels share the bin's list (and its cache lines).
#define S3D_RAYCAST_GROUP_SIZE S3D_RAYCAST_BIN_SIZE
#define S3D_RAYCAST_BIN_CAPACITY 64
// A triangle whose bounds span more bins than this is binned by a workgroup of its own (the indirect pass).
#define S3D_RAYCAST_BIN_DIRECT 8
// RaycastSearch::Automatic bins a tree of at most this many triangle references per bin of the view.
#define S3D_RAYCAST_BIN_AUTO_REFERENCES 4
#define S3D_RAYCAST_BIN_GROUP 256
#define S3D_RAYCAST_BIN_SPLIT 8  // workgroups per large triangle

// The indirect pass's arguments and the large triangles it bins (std430).
struct RaycastBinLarge {
  uvec4 dispatch;  // x: workgroups (the queued triangles, at most 65535), y: S3D_RAYCAST_BIN_SPLIT, z: 1,
                   // w: the queued triangles
};

// One pixel ray of one layer, what its leaf tests need: the ray from the near plane (t 0) to the far plane (t 1)
// in layer space, and the raster view of the same sample.
struct PixelRay {
  vec3 origin;
  vec3 direction;
  mat4 viewProjection;  // layer space -> clip, as the raster pass projects
  vec4 screen;          // width, height, 1 / width, 1 / height
  ivec2 subpixel;       // the sample in framebuffer coordinates, 1 / S3D_SUBPIXEL_UNITS pixel units
  vec2 depthRange;      // the layer's viewport depth range
  vec4 depthToT;        // x, y: w of the ray's clip-to-layer point at ndc z 0 and its change per unit z; z, w: the
                        // ndc z of t 0 and t 1 (see rayParameterOf)
  float nearer;         // 1: a smaller device depth is nearer (LESS), -1: a larger one (reversed depth, GREATER)
};

// A triangle as the rasterizer sets it up for one view (setupTriangle; 64 bytes, std430): its polygon after the
// near-plane clip, snapped to the sub-pixel grid (framebuffer positions in 1 / S3D_SUBPIXEL_UNITS pixels), ordered
// clockwise, with its vertices' ndc depths. The ray-cast pass sets every triangle up once per view
// (raycast_setup.comp), so each ray's leaf test only evaluates its edge functions (coverSample).
#define S3D_SNAPPED_NEVER 0u     // covers no sample: culled, zero snapped area, or clipped away
#define S3D_SNAPPED_POLYGON 1u   // the rasterizer's rule decides each sample
#define S3D_SNAPPED_RAY_TEST 2u  // undecided here: past S3D_RASTER_REACH, w <= 0, or a degenerate clipped polygon
struct SnappedTriangle {
  ivec4 xy01;   // vertices 0 and 1 (x, y)
  ivec4 xy23;   // vertices 2 and 3 (the fourth only for a clipped quadrilateral)
  vec4 z;       // the vertices' ndc depths
  uvec4 shape;  // x: the vertex count (3 or 4), y: S3D_SNAPPED_*; z, w: 0
};

// A point of the pixel ray: the layer-space position of normalized device coordinates (ndc, z); z 0 and 1 give
// the ray's ends on the near and far planes (far and near under reversed depth: pixelRayOf starts at the near).
// Matrix products are spelled out column by column so both compilers evaluate them in the same order.
S3D_INLINE vec3 unprojectNdc(mat4 clipToLayer, vec2 ndc, float z) {
  S3D_PRECISE vec4 p = clipToLayer[0] * ndc.x + clipToLayer[1] * ndc.y + clipToLayer[2] * z + clipToLayer[3];
  return vec3(p.x, p.y, p.z) / p.w;
}

// The normalized device coordinates of a sample given in 1 / S3D_SUBPIXEL_UNITS pixels (a pixel's centre:
// pixel * S3D_SUBPIXEL_UNITS + S3D_SUBPIXEL_UNITS / 2).
S3D_INLINE vec2 subpixelNdc(ivec2 subpixel, vec4 screen) {
  vec2 pixels = vec2(float(subpixel.x), float(subpixel.y)) * (1.0f / float(S3D_SUBPIXEL_UNITS));
  return pixels * vec2(screen.z, screen.w) * 2.0f - 1.0f;
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

// Möller-Trumbore: the ray parameter t of the hit, or infinity; for the triangles rasterCoverage leaves undecided.
// Edges and vertices count as inside (u, v >= 0, u + v <= 1), so a ray through a shared edge hits both triangles
// at the same depth and the tie rule (closerHit) picks one. A back face (the vertices clockwise as seen along the ray: det <= 0) is culled unless the triangle
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

// The ray parameter t where the ray meets the plane of the triangle, or infinity for a ray along it: the depth of a
// hit the rasterizer's rule covered. One rounding from the exact point (as the rasterizer's depth of the vertices'
// own plane is), where an interpolation on the snapped vertices would lose float steps on far surfaces.
S3D_INLINE float intersectPlane(vec3 origin, vec3 direction, vec3 v0, vec3 v1, vec3 v2) {
  S3D_PRECISE vec3 normal = cross(v1 - v0, v2 - v0);
  S3D_PRECISE float along = dot(direction, normal);
  if (along == 0.0f) return S3D_INFINITY;
  S3D_PRECISE float distance = dot(v0 - origin, normal);
  return distance / along;
}

// The sign of a * b - c * d, exact for any 32-bit integers (64-bit products).
S3D_INLINE int productDifferenceSign(int a, int b, int c, int d) {
  int high1 = 0, low1 = 0, high2 = 0, low2 = 0;
  imulExtended(a, b, high1, low1);
  imulExtended(c, d, high2, low2);
  if (high1 != high2) return high1 < high2 ? -1 : 1;
  if (low1 == low2) return 0;
  return uint(low1) < uint(low2) ? -1 : 1;
}

// Whether the edge from p to q (sample-relative snapped positions of a polygon ordered clockwise on screen,
// framebuffer y down, so its inside is on the positive side of every edge) admits the sample: its edge function
// is positive, or zero on a top or left edge (the top-left rule: a sample on an edge shared by two triangles
// belongs to exactly one of them).
S3D_INLINE bool edgeAdmits(ivec2 p, ivec2 q) {
  int side = productDifferenceSign(p.x, q.y, q.x, p.y);
  if (side != 0) return side > 0;
  return q.y < p.y || (q.y == p.y && q.x > p.x);
}

// A clip-space position as the rasterizer sees it: snapped framebuffer position and ndc depth. False past
// S3D_RASTER_REACH (where the rasterizer clips at its guard band) or at w <= 0.
S3D_INLINE bool snapClip(vec4 screen, vec4 clip, S3D_OUT(ivec2) snapped, S3D_OUT(float) depth) {
  if (!(clip.w > 0.0f)) return false;
  S3D_PRECISE float reciprocal = 1.0f / clip.w;
  S3D_PRECISE vec3 ndc = vec3(clip.x, clip.y, clip.z) * reciprocal;
  S3D_PRECISE vec2 halfSize = vec2(screen.x, screen.y) * 0.5f;
  S3D_PRECISE vec2 framebuffer = vec2(fma(ndc.x, halfSize.x, halfSize.x), fma(ndc.y, halfSize.y, halfSize.y));
  if (!(abs(framebuffer.x) < S3D_RASTER_REACH && abs(framebuffer.y) < S3D_RASTER_REACH)) return false;
  S3D_PRECISE vec2 units = framebuffer * float(S3D_SUBPIXEL_UNITS);
  snapped = ivec2(int(roundEven(units.x)), int(roundEven(units.y)));
  depth = ndc.z;
  return true;
}

// The ndc depth at the sample of the plane through three snapped vertices (weights: each vertex's opposite edge
// function there), and whether the sample lies inside or on that triangle. Interpolated as z0 plus the weighted
// differences: far surfaces' depths lie within a few float steps of 1 (of 0 reversed), where a weighted sum of the
// depths themselves loses several steps, each step there tens of metres that the lighting reconstructs.
S3D_INLINE bool interpolateDepth(ivec2 p0, ivec2 p1, ivec2 p2, float z0, float z1, float z2, S3D_OUT(float) z) {
  S3D_PRECISE float w0 = float(p1.x) * float(p2.y) - float(p2.x) * float(p1.y);
  S3D_PRECISE float w1 = float(p2.x) * float(p0.y) - float(p0.x) * float(p2.y);
  S3D_PRECISE float w2 = float(p0.x) * float(p1.y) - float(p1.x) * float(p0.y);
  S3D_PRECISE float change = w1 * (z1 - z0) + w2 * (z2 - z0);
  z = z0 + change / (w0 + w1 + w2);
  return w0 >= 0.0f && w1 >= 0.0f && w2 >= 0.0f;
}

// The barycentrics (of v0, v1, v2) where the ray's line meets the triangle's plane: the perspective-correct
// weights the raster pass interpolates with at the ray's sample (Möller-Trumbore's u, v, without its range
// tests); a triangle seen edge-on gets its centroid.
S3D_INLINE vec3 rayBarycentrics(vec3 origin, vec3 direction, vec3 v0, vec3 v1, vec3 v2) {
  vec3 e1 = v1 - v0;
  vec3 e2 = v2 - v0;
  vec3 p = cross(direction, e2);
  float det = dot(e1, p);
  if (det == 0.0f) return vec3(1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f);
  vec3 s = origin - v0;
  float u = dot(s, p) / det;
  float v = dot(direction, cross(s, e1)) / det;
  return vec3(1.0f - u - v, u, v);
}

// How the rasterizer sets a triangle up for a view (m: its layer's view-projection; nearer: PixelRay::nearer):
// clipped at the near plane in clip space (into a polygon of up to 4 vertices, as the rasterizer clips it) and
// snapped; past the far plane its edges stay the triangle's own (coverSample drops samples whose depth lies beyond).
// Front faces are counter-clockwise in the framebuffer (VK_FRONT_FACE_COUNTER_CLOCKWISE); back faces (but
// double-sided ones) and polygons of zero snapped area never cover. Left to the ray test: a vertex past
// S3D_RASTER_REACH, or a clipped polygon whose first three vertices snap onto one line.
S3D_INLINE SnappedTriangle setupTriangle(mat4 m, vec4 screen, float nearer, vec3 v0, vec3 v1, vec3 v2, uint flags) {
  SnappedTriangle snapped;
  snapped.xy01 = ivec4(0, 0, 0, 0);
  snapped.xy23 = ivec4(0, 0, 0, 0);
  snapped.z = vec4(0.0f, 0.0f, 0.0f, 0.0f);
  snapped.shape = uvec4(0u, S3D_SNAPPED_NEVER, 0u, 0u);
  vec4 corner[3];
  S3D_PRECISE vec4 c0 = m[0] * v0.x + m[1] * v0.y + m[2] * v0.z + m[3];
  S3D_PRECISE vec4 c1 = m[0] * v1.x + m[1] * v1.y + m[2] * v1.z + m[3];
  S3D_PRECISE vec4 c2 = m[0] * v2.x + m[1] * v2.y + m[2] * v2.z + m[3];
  corner[0] = c0;
  corner[1] = c1;
  corner[2] = c2;
  vec4 polygon[4];
  int n = 0;
  for (int i = 0; i < 3; ++i) {  // Sutherland-Hodgman against the near plane (distance >= 0 inside)
    vec4 a = corner[i], b = corner[(i + 1) % 3];
    S3D_PRECISE float da = nearer > 0.0f ? a.z : a.w - a.z;
    S3D_PRECISE float db = nearer > 0.0f ? b.z : b.w - b.z;
    if (da >= 0.0f) polygon[n++] = a;
    if ((da >= 0.0f) != (db >= 0.0f)) {
      S3D_PRECISE float s = da / (da - db);
      S3D_PRECISE vec4 crossing = a + (b - a) * s;
      polygon[n++] = crossing;
    }
  }
  if (n < 3) return snapped;
  ivec2 p[4];
  float z[4];
  for (int i = 0; i < n; ++i)
    if (!snapClip(screen, polygon[i], p[i], z[i])) {
      snapped.shape.y = S3D_SNAPPED_RAY_TEST;
      return snapped;
    }
  int area = productDifferenceSign(p[1].x - p[0].x, p[2].y - p[0].y, p[1].y - p[0].y, p[2].x - p[0].x);  // > 0: clockwise
  if (area == 0) {
    if (n == 4) snapped.shape.y = S3D_SNAPPED_RAY_TEST;
    return snapped;
  }
  if (area > 0 && (flags & S3D_BVH_DOUBLE_SIDED) == 0u) return snapped;
  if (area < 0) {  // a front face: order it clockwise so that the inside is on every edge's positive side
    ivec2 q = p[1];
    p[1] = p[n - 1];
    p[n - 1] = q;
    float y = z[1];
    z[1] = z[n - 1];
    z[n - 1] = y;
  }
  if (n == 3) {
    p[3] = p[2];
    z[3] = z[2];
  }
  snapped.xy01 = ivec4(p[0].x, p[0].y, p[1].x, p[1].y);
  snapped.xy23 = ivec4(p[2].x, p[2].y, p[3].x, p[3].y);
  snapped.z = vec4(z[0], z[1], z[2], z[3]);
  snapped.shape = uvec4(uint(n), S3D_SNAPPED_POLYGON, 0u, 0u);
  return snapped;
}

// A set-up triangle's verdict at a sample (1 / S3D_SUBPIXEL_UNITS pixel units): 1 covered (ndcDepth: its depth
// there, interpolated linearly in the framebuffer as the rasterizer does), 0 not covered, -1 undecided: ask the
// ray test. Every snapped edge, relative to the sample, must admit it.
S3D_INLINE int coverSample(SnappedTriangle snapped, ivec2 at, S3D_OUT(float) ndcDepth) {
  if (snapped.shape.y == S3D_SNAPPED_NEVER) return 0;
  if (snapped.shape.y == S3D_SNAPPED_RAY_TEST) return -1;
  int n = int(snapped.shape.x);
  ivec2 p[4];
  p[0] = ivec2(snapped.xy01.x, snapped.xy01.y) - at;
  p[1] = ivec2(snapped.xy01.z, snapped.xy01.w) - at;
  p[2] = ivec2(snapped.xy23.x, snapped.xy23.y) - at;
  p[3] = ivec2(snapped.xy23.z, snapped.xy23.w) - at;
  for (int i = 0; i < n; ++i)
    if (!edgeAdmits(p[i], p[(i + 1) % n])) return 0;
  // The depth of the fan triangle (as the rasterizer splits the polygon) that holds the sample.
  float depth = 0.0f;
  if (!interpolateDepth(p[0], p[1], p[2], snapped.z.x, snapped.z.y, snapped.z.z, depth) && n == 4)
    interpolateDepth(p[0], p[2], p[3], snapped.z.x, snapped.z.z, snapped.z.w, depth);
  if (!(depth >= 0.0f && depth <= 1.0f)) return 0;  // clipped away at the far plane
  ndcDepth = depth;
  return 1;
}

// Both steps for one ray (the C++ reference's way; the GPU pass sets every triangle up once per view).
S3D_INLINE int rasterCoverage(PixelRay ray, vec3 v0, vec3 v1, vec3 v2, uint flags, S3D_OUT(float) ndcDepth) {
  return coverSample(setupTriangle(ray.viewProjection, ray.screen, ray.nearer, v0, v1, v2, flags), ray.subpixel,
                     ndcDepth);
}

// The ray parameter of the point of the pixel ray at ndc depth z (the unprojection is a ratio of linear functions
// of z, so t is too): lets a raster-decided hit prune the traversal as a ray hit does.
S3D_INLINE float rayParameterOf(vec4 depthToT, float z) {
  S3D_PRECISE float a = depthToT.x, b = depthToT.y, zStart = depthToT.z, zEnd = depthToT.w;
  return (z - zStart) / (zEnd - zStart) * (a + zEnd * b) / (a + z * b);
}

// The pixels whose centres a set-up triangle may cover: xy the first, zw the last (inclusive, clamped to the
// screen; empty when z < x or w < y). A polygon's samples lie within its snapped bounds; a triangle left to the
// ray test may cover any pixel.
S3D_INLINE ivec4 snappedPixelBounds(SnappedTriangle snapped, vec4 screen) {
  ivec2 last = ivec2(int(screen.x) - 1, int(screen.y) - 1);
  if (snapped.shape.y == S3D_SNAPPED_NEVER) return ivec4(0, 0, -1, -1);
  if (snapped.shape.y == S3D_SNAPPED_RAY_TEST) return ivec4(0, 0, last.x, last.y);
  ivec2 lo = min(min(ivec2(snapped.xy01.x, snapped.xy01.y), ivec2(snapped.xy01.z, snapped.xy01.w)),
                 ivec2(snapped.xy23.x, snapped.xy23.y));
  ivec2 hi = max(max(ivec2(snapped.xy01.x, snapped.xy01.y), ivec2(snapped.xy01.z, snapped.xy01.w)),
                 ivec2(snapped.xy23.x, snapped.xy23.y));
  if (snapped.shape.x == 4u) {
    lo = min(lo, ivec2(snapped.xy23.z, snapped.xy23.w));
    hi = max(hi, ivec2(snapped.xy23.z, snapped.xy23.w));
  }
  // Pixel p's centre lies at p * units + units / 2: the first centre at or past lo, the last at or before hi.
  const int centre = S3D_SUBPIXEL_UNITS / 2;
  ivec2 first = max((lo - centre + (S3D_SUBPIXEL_UNITS - 1)) >> S3D_SUBPIXEL_BITS, ivec2(0, 0));
  ivec2 lastCentre = min((hi - centre) >> S3D_SUBPIXEL_BITS, last);
  return ivec4(first.x, first.y, lastCentre.x, lastCentre.y);
}

// The tie rule of the closest hit, on depth keys (device depth times PixelRay::nearer): the smaller key; at equal
// keys the smaller ray parameter (far surfaces metres apart share one float depth, and the raster pass draws
// front to back, so the nearer of them is drawn first and kept), then (coplanar overlaps; shared edges never tie,
// the top-left rule gives their samples to one triangle) the lower object index, then the lower triangle index,
// whatever order the traversal meets them in.
S3D_INLINE bool closerHit(float key, float t, uint object, uint triangle, float bestKey, float bestT, uint bestObject,
                          uint bestTriangle) {
  if (key != bestKey) return key < bestKey;
  if (t != bestT) return t < bestT;
  return object != bestObject ? object < bestObject : triangle < bestTriangle;
}

// The device depth the raster pass writes at ndc depth z: the viewport maps it into the layer's range.
S3D_INLINE float deviceDepthAt(float z, vec2 depthRange) { return depthRange.x + z * (depthRange.y - depthRange.x); }

// The device depth the raster pass writes for a layer-space point.
S3D_INLINE float deviceDepthOf(mat4 viewProjection, vec3 point, vec2 depthRange) {
  S3D_PRECISE vec4 clip = viewProjection[0] * point.x + viewProjection[1] * point.y + viewProjection[2] * point.z +
                         viewProjection[3];
  return deviceDepthAt(clip.z / clip.w, depthRange);
}

// The pixel ray of one layer through a sample (1 / S3D_SUBPIXEL_UNITS pixel units), from the near to the far plane.
S3D_INLINE PixelRay pixelRayOf(mat4 clipToLayer, mat4 viewProjection, vec4 screen, ivec2 subpixel, vec2 depthRange,
                               float nearer) {
  PixelRay ray;
  vec2 ndc = subpixelNdc(subpixel, screen);
  float zStart = nearer > 0.0f ? 0.0f : 1.0f;
  ray.origin = unprojectNdc(clipToLayer, ndc, zStart);
  ray.direction = unprojectNdc(clipToLayer, ndc, 1.0f - zStart) - ray.origin;
  ray.viewProjection = viewProjection;
  ray.screen = screen;
  ray.subpixel = subpixel;
  ray.depthRange = depthRange;
  S3D_PRECISE float a = clipToLayer[0].w * ndc.x + clipToLayer[1].w * ndc.y + clipToLayer[3].w;
  ray.depthToT = vec4(a, clipToLayer[2].w, zStart, 1.0f - zStart);
  ray.nearer = nearer;
  return ray;
}

// A triangle's hit by a pixel ray, decided as the rasterizer decides its sample (rasterCoverage), or by the ray
// test (intersectTriangle) where the rasterizer clips the triangle: its ray parameter t (which prunes the
// traversal) and device depth (which picks the closest hit, as the depth test does).
S3D_INLINE bool leafHitSetUp(PixelRay ray, SnappedTriangle snapped, vec3 v0, vec3 v1, vec3 v2, uint flags, S3D_OUT(float) t,
                              S3D_OUT(float) depth) {
  float z = 0.0f;
  int coverage = coverSample(snapped, ray.subpixel, z);
  if (coverage == 0) return false;
  if (coverage > 0) {
    t = intersectPlane(ray.origin, ray.direction, v0, v1, v2);
    if (t >= 0.0f && t <= 1.0f) {
      S3D_PRECISE vec3 point = ray.origin + t * ray.direction;
      depth = deviceDepthOf(ray.viewProjection, point, ray.depthRange);
    } else {  // covered on the snapped vertices only (the ray grazes the plane's edge): their interpolation
      t = rayParameterOf(ray.depthToT, z);
      depth = deviceDepthAt(z, ray.depthRange);
    }
    return true;
  }
  t = intersectTriangle(ray.origin, ray.direction, v0, v1, v2, flags);
  if (!(t <= 1.0f)) return false;
  S3D_PRECISE vec3 point = ray.origin + t * ray.direction;
  depth = deviceDepthOf(ray.viewProjection, point, ray.depthRange);
  return true;
}

// The same with the triangle set up for this ray's view here (the C++ reference).
S3D_INLINE bool leafHit(PixelRay ray, vec3 v0, vec3 v1, vec3 v2, uint flags, S3D_OUT(float) t, S3D_OUT(float) depth) {
  return leafHitSetUp(ray, setupTriangle(ray.viewProjection, ray.screen, ray.nearer, v0, v1, v2, flags), v0, v1, v2,
                      flags, t, depth);
}

// How far past the best hit's t the traversal still enters a box: a raster-decided hit's t comes from its
// interpolated depth on snapped vertices, which can lie a little before the ray's own hit of the same surface.
S3D_INLINE float pruneLimit(float bestT) { return min(bestT * (1.0f + 1.0f / 256.0f), 1.0f); }

S3D_GPU_END

#endif  // S3D_RAYCAST_SHARED_H
