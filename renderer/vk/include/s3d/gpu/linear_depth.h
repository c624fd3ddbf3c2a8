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
};

S3D_INLINE float linearDepthFromDevice(LinearDepthParams p, float deviceDepth) {
  if (deviceDepth >= p.skyDeviceDepth) return S3D_INFINITY;
  // step(edge, x) is 1 when x >= edge: first-person when deviceDepth <= firstPersonDeviceDepthMax.
  float isFirstPerson = step(deviceDepth, p.firstPersonDeviceDepthMax);
  vec2 ratio = mix(p.worldRatio, p.firstPersonRatio, isFirstPerson);
  return ratio.y / (deviceDepth - ratio.x);
}

// The depth the stereo pass sees: linear depth, with the first-person layer pushed into the screen by
// offsetting and scaling its depth (seed 4.6.2). Per pixel, so the weapon's own visibility is untouched.
S3D_INLINE float stereoDepthFromDevice(LinearDepthParams p, float deviceDepth) {
  float depth = linearDepthFromDevice(p, deviceDepth);
  if (deviceDepth <= p.firstPersonDeviceDepthMax) depth = p.firstPersonDepthOffset + p.firstPersonDepthScale * depth;
  return depth;
}

// Reversed Z (near plane at device depth 1, far plane at 0, cleared to 0 for sky): its device depth is a
// standard zero-to-one projection's with near and far swapped, so Listing 4.2's d = y / (z - x) holds
// unchanged with the swapped ratio (reversedProjectionRatio). Device depth <= 0 is sky.
S3D_INLINE float linearDepthFromReversedDevice(vec2 reversedRatio, float deviceDepth) {
  if (deviceDepth <= 0.0f) return S3D_INFINITY;
  return reversedRatio.y / (deviceDepth - reversedRatio.x);
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
#endif

S3D_GPU_END

#endif  // S3D_GPU_LINEAR_DEPTH_H
