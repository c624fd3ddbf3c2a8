// Nonlinear depth-to-parallax mapping (disparity_map.h): the monotonic curve, shared by the compute shader that
// applies it to the stereo pass's depth and by the C++ reference, so both map every depth the same way.
//
// The stereo pass gives a pixel at linear depth d the parallax m (1 - zpp u) with u = 1 / d: linear in inverse
// depth. The map replaces u by w(u), piecewise linear through knots (u_i, w_i) and with slope 1 beyond the end
// knots, and the depth by 1 / w(u). Every method (seed, search, iterative, forward, hybrid) computes parallax
// from the depth it reads through parallaxFromDepth, so mapping that depth maps all of them alike.
#ifndef S3D_DISPARITY_MAP_SHARED_H
#define S3D_DISPARITY_MAP_SHARED_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_DISPARITY_MAP_KNOTS 8
#define S3D_DISPARITY_MAP_GROUP_SIZE 8

// Push constants (112 bytes; scalars and float arrays only, so the std430 and C++ layouts agree).
struct DisparityMapConstants {
  int knotCount;  // < 2: the identity (the linear mapping)
  int padding0;
  int padding1;
  int padding2;
  float inverseDepth[S3D_DISPARITY_MAP_KNOTS];  // u_i, strictly increasing (far to near)
  float mapped[S3D_DISPARITY_MAP_KNOTS];        // w_i, strictly increasing
  float slope[S3D_DISPARITY_MAP_KNOTS];         // (w_i+1 - w_i) / (u_i+1 - u_i): segment i, from u_i
};

// w(u): exactly w_i at u_i (the segment starting there adds 0), never past the next knot's w (float rounding
// cannot break monotonicity), never below 0 (the sky, u = 0, stays at infinity when w_0 = u_0 or u_0 = 0).
S3D_INLINE float mapInverseDepth(DisparityMapConstants map, float u) {
  if (map.knotCount < 2) return u;
  const int last = map.knotCount - 1;
  float w;
  if (u < map.inverseDepth[0]) {
    w = map.mapped[0] + (u - map.inverseDepth[0]);
  } else if (u >= map.inverseDepth[last]) {
    w = map.mapped[last] + (u - map.inverseDepth[last]);
  } else {
    int i = 0;
    for (int k = 1; k < last; ++k)
      if (u >= map.inverseDepth[k]) i = k;
    w = min(map.mapped[i] + (u - map.inverseDepth[i]) * map.slope[i], map.mapped[i + 1]);
  }
  return max(w, 0.0f);
}

// The depth the stereo pass reads instead of `linearDepth`: 1 / w(1 / d), written d (u / w) so a depth the map
// keeps (w = u, e.g. at the fixed knots and beyond the nearest one) comes back bit for bit. Invalid depth (NaN,
// zero, negative) stays as it is (the stereo pass reads it as the zero-parallax plane); the sky (+inf, u = 0)
// stays at infinity when w(0) = 0.
S3D_INLINE float mappedDepth(DisparityMapConstants map, float linearDepth) {
  if (!(linearDepth > 0.0f) || map.knotCount < 2) return linearDepth;
  const float u = 1.0f / linearDepth;
  const float w = mapInverseDepth(map, u);
  if (!(w > 0.0f)) return S3D_INFINITY;
  return u > 0.0f ? linearDepth * (u / w) : 1.0f / w;
}

S3D_GPU_END

#endif  // S3D_DISPARITY_MAP_SHARED_H
