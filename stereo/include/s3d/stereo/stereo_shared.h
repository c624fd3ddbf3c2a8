// Stereo-pass parameters and math shared by the compute shader and the C++ reference implementation.
#ifndef S3D_STEREO_SHARED_H
#define S3D_STEREO_SHARED_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_STEREO_MAX_TAPS 16  // keeps the push constants within the guaranteed 128 bytes
#define S3D_STEREO_SMALL_TAP_CAPACITY 4  // the seed's 3 taps: a pipeline with a short tap array
#define S3D_STEREO_GROUP_SIZE 8

// The tap array's length as compiled: C++ always holds the maximum; each shader variant defines its own
// (a long push-constant array slowed the 3-tap seed on lavapipe), and because the
// array comes last, every variant reads the same prefix.
#ifndef S3D_STEREO_TAP_CAPACITY
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_MAX_TAPS
#endif

// Push constants of the stereo pass; scalars only, so the std430 and C++ layouts agree.
struct StereoConstants {
  int tapCount;
  float maxSeparation;         // fraction of the screen width
  float zeroParallaxDistance;  // world units, same as the linear depth
  int cropBegin;               // columns [0, cropBegin) are written black
  int cropEnd;                 // columns [cropEnd, width) are written black
  int width;
  int height;
  int padding0;
  int tapOffsetPx[S3D_STEREO_TAP_CAPACITY];  // depth-search offsets in whole pixels (Listing 4.5's taps * width)
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
