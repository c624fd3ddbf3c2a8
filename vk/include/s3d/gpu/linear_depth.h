// Device depth -> linear view depth, shared by C++ and GLSL (Listings 4.2 and 4.3).
#ifndef S3D_GPU_LINEAR_DEPTH_H
#define S3D_GPU_LINEAR_DEPTH_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

// Listing 4.3: the world and the first-person layer have their own projection and device-depth range.
// ratio.x/ratio.y are Listing 4.2's ProjRatio in world units, already remapped to the layer's viewport depth
// range [a, b]: x' = a + x (b - a), y' = y (b - a) with x = f / (f - n), y = n f / (n - f).
struct LinearDepthParams {
  vec2 worldRatio;
  vec2 firstPersonRatio;
  float firstPersonDeviceDepthMax;  // device depth <= this belongs to the first-person layer
  float skyDeviceDepth;             // device depth >= this is sky at infinite distance (the cleared far plane)
  float firstPersonDepthOffset;     // seed 4.6.2 weapon push, for stereoDepthFromDevice only
  float firstPersonDepthScale;
  // 1: reversed-Z depth buffer (makeReversedLinearDepthParams): near at 1, far and sky at 0, the world in
  // [0, 1 - firstPersonDeviceDepthMax] and the first-person layer in [1 - firstPersonDeviceDepthMax, 1].
  float reversedZ;
  float padding0;
  float padding1;
  float padding2;
};

S3D_INLINE float linearDepthFromDevice(LinearDepthParams p, float deviceDepth) {
  if (deviceDepth >= p.skyDeviceDepth) return S3D_INFINITY;
  // step(edge, x) is 1 when x >= edge: first-person when deviceDepth <= firstPersonDeviceDepthMax.
  float isFirstPerson = step(deviceDepth, p.firstPersonDeviceDepthMax);
  vec2 ratio = mix(p.worldRatio, p.firstPersonRatio, isFirstPerson);
  return ratio.y / (deviceDepth - ratio.x);
}

// Reversed-Z: each layer's projection has near and far swapped, so its ratio is projectionRatio(far, near, ...)
// and Listing 4.3's ratio.y / (d - ratio.x) holds unchanged; only the sky (cleared to 0) and the layer split
// (first-person above 1 - split) read the other way. Far depths land near 0, where floats are densest.
S3D_INLINE float linearDepthFromReversedDevice(LinearDepthParams p, float deviceDepth) {
  if (deviceDepth <= p.skyDeviceDepth) return S3D_INFINITY;
  // step(edge, x) is 1 when x >= edge: first-person when deviceDepth >= 1 - firstPersonDeviceDepthMax.
  float isFirstPerson = step(1.0f - p.firstPersonDeviceDepthMax, deviceDepth);
  vec2 ratio = mix(p.worldRatio, p.firstPersonRatio, isFirstPerson);
  return ratio.y / (deviceDepth - ratio.x);
}

// Either depth convention, as p says: what the renderer's passes call.
S3D_INLINE bool isSkyDeviceDepth(LinearDepthParams p, float deviceDepth) {
  return p.reversedZ != 0.0f ? deviceDepth <= p.skyDeviceDepth : deviceDepth >= p.skyDeviceDepth;
}
S3D_INLINE bool isFirstPersonDeviceDepth(LinearDepthParams p, float deviceDepth) {
  return p.reversedZ != 0.0f ? deviceDepth >= 1.0f - p.firstPersonDeviceDepthMax
                             : deviceDepth <= p.firstPersonDeviceDepthMax;
}
S3D_INLINE float linearDepthFromDepthBuffer(LinearDepthParams p, float deviceDepth) {
  return p.reversedZ != 0.0f ? linearDepthFromReversedDevice(p, deviceDepth) : linearDepthFromDevice(p, deviceDepth);
}

// A depth buffer's value with the convention folded in: within one layer a smaller key is nearer, so the layer,
// sky and range tests below read the same in both conventions.
S3D_INLINE float deviceDepthKey(LinearDepthParams p, float deviceDepth) {
  return p.reversedZ != 0.0f ? -deviceDepth : deviceDepth;
}
// Keys at or below this belong to the first-person layer (isFirstPersonDeviceDepth in keys).
S3D_INLINE float firstPersonKeyMax(LinearDepthParams p) {
  return p.reversedZ != 0.0f ? p.firstPersonDeviceDepthMax - 1.0f : p.firstPersonDeviceDepthMax;
}
// The key of the depth range's near end (device depth 0, or 1 reversed).
S3D_INLINE float deviceDepthKeyMin(LinearDepthParams p) { return p.reversedZ != 0.0f ? -1.0f : 0.0f; }
// Device depth nearer than the depth range's near end and NaN are no surface. Keys from deviceDepthKeyMin up
// convert to positive depths that never decrease with the key within a layer; false for NaN.
S3D_INLINE bool isDeviceDepthKeyInRange(LinearDepthParams p, float key) { return key >= deviceDepthKeyMin(p); }
// No device depth in range belongs to the first-person layer (the host gave it no depth range of its own).
S3D_INLINE bool hasNoFirstPersonLayer(LinearDepthParams p) { return firstPersonKeyMax(p) < deviceDepthKeyMin(p); }

// The depth the stereo pass sees: linear depth, with the first-person layer pushed into the screen by
// offsetting and scaling its depth (seed 4.6.2). Per pixel, so the weapon's own visibility is untouched.
// Out-of-range device depth reads 0, which the stereo pass takes as the zero-parallax plane (sanitizedDepth).
// Branch-free with one division: the stereo gather converts every depth tap of a host's buffer with it.
S3D_INLINE float stereoDepthFromDevice(LinearDepthParams p, float deviceDepth) {
  float key = deviceDepthKey(p, deviceDepth);
  bool firstPerson = key <= firstPersonKeyMax(p);
  vec2 ratio = firstPerson ? p.firstPersonRatio : p.worldRatio;
  float offset = firstPerson ? p.firstPersonDepthOffset : 0.0f;
  float scale = firstPerson ? p.firstPersonDepthScale : 1.0f;
  float depth = offset + scale * ratio.y / (deviceDepth - ratio.x);  // Listing 4.3, then the push
  depth = key >= deviceDepthKey(p, p.skyDeviceDepth) ? S3D_INFINITY : depth;
  return isDeviceDepthKeyInRange(p, key) ? depth : 0.0f;
}

#ifdef __cplusplus
// Listing 4.2's ProjRatio for a zero-to-one perspective projection (near n, far f, world units) whose depth
// is written into the viewport depth range [rangeBegin, rangeEnd].
inline vec2 projectionRatio(float n, float f, float rangeBegin, float rangeEnd) {
  float x = f / (f - n);
  float y = n * f / (n - f);
  return {rangeBegin + x * (rangeEnd - rangeBegin), y * (rangeEnd - rangeBegin)};
}

// ProjRatio of a reversed-Z projection (near n -> rangeEnd, far f -> rangeBegin): the standard one, swapped.
inline vec2 reversedProjectionRatio(float n, float f, float rangeBegin, float rangeEnd) {
  return projectionRatio(f, n, rangeBegin, rangeEnd);
}

// World depth lives in [firstPersonDeviceDepthMax, 1], first-person depth in [0, firstPersonDeviceDepthMax].
inline LinearDepthParams makeLinearDepthParams(float worldNear, float worldFar, float firstPersonNear,
                                               float firstPersonFar, float firstPersonDeviceDepthMax) {
  LinearDepthParams p{};
  p.worldRatio = projectionRatio(worldNear, worldFar, firstPersonDeviceDepthMax, 1.0f);
  p.firstPersonRatio = projectionRatio(firstPersonNear, firstPersonFar, 0.0f, firstPersonDeviceDepthMax);
  p.firstPersonDeviceDepthMax = firstPersonDeviceDepthMax;
  p.skyDeviceDepth = 1.0f;
  p.firstPersonDepthOffset = 0.0f;
  p.firstPersonDepthScale = 1.0f;
  return p;
}

// Reversed-Z: the world in [0, 1 - split] and first-person depth in [1 - split, 1], near planes at the top of
// each range; the cleared 0 is the sky. firstPersonDeviceDepthMax keeps the split (the first-person share).
inline LinearDepthParams makeReversedLinearDepthParams(float worldNear, float worldFar, float firstPersonNear,
                                                       float firstPersonFar, float firstPersonDeviceDepthMax) {
  LinearDepthParams p = makeLinearDepthParams(worldNear, worldFar, firstPersonNear, firstPersonFar,
                                              firstPersonDeviceDepthMax);
  const float split = 1.0f - firstPersonDeviceDepthMax;
  p.worldRatio = projectionRatio(worldFar, worldNear, 0.0f, split);
  p.firstPersonRatio = projectionRatio(firstPersonFar, firstPersonNear, split, 1.0f);
  p.skyDeviceDepth = 0.0f;
  p.reversedZ = 1.0f;
  return p;
}
#endif

S3D_GPU_END

#endif  // S3D_GPU_LINEAR_DEPTH_H
