// Stereo-pass parameters and math shared by the compute shader and the C++ reference implementation.
#ifndef S3D_STEREO_SHARED_H
#define S3D_STEREO_SHARED_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_STEREO_MAX_TAPS 16  // keeps the push constants within the guaranteed 128 bytes
#define S3D_STEREO_GROUP_SIZE 8

// Push constants of the stereo pass; scalars only, so the std430 and C++ layouts agree.
struct StereoConstants {
  int tapOffsetPx[S3D_STEREO_MAX_TAPS];  // depth-search offsets in whole pixels (Listing 4.5's taps * width)
  int tapCount;
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units, same as the linear depth
  int cropBegin;               // columns [0, cropBegin) are written black
  int cropEnd;                 // columns [cropEnd, width) are written black
  int width;
  int height;
  int padding0;
};

// Figure 4.34: Parallax = MaxSeparation * (1 - ZPP / Depth), as a fraction of the screen width.
// Sky (+inf depth) gives exactly maxSeparation.
S3D_INLINE float parallaxFromDepth(float maxSeparation, float zeroParallaxDistance, float linearDepth) {
  return maxSeparation * (1.0f - zeroParallaxDistance / linearDepth);
}

// Depth that carries no information (NaN, zero, negative) is read as the zero-parallax distance: the
// pixel then stays where it is instead of spreading NaN or jumping by a meaningless parallax.
S3D_INLINE float sanitizedDepth(float linearDepth, float zeroParallaxDistance) {
  return linearDepth > 0.0f ? linearDepth : zeroParallaxDistance;
}

S3D_GPU_END

#endif  // S3D_STEREO_SHARED_H
