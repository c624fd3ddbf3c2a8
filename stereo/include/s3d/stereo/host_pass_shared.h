// Push constants of the host pass's input conversion and output packing, shared by the shaders and C++.
#ifndef S3D_STEREO_HOST_PASS_SHARED_H
#define S3D_STEREO_HOST_PASS_SHARED_H

#include "s3d/gpu/linear_depth.h"

S3D_GPU_BEGIN

#define S3D_HOST_GROUP_SIZE 8

// How the sampled host colour becomes the stereo kernel's colour.
#define S3D_HOST_COLOR_AS_STORED 0  // UNORM views (RGBA8, BGRA8) and HDR formats: the values as sampled
#define S3D_HOST_COLOR_ENCODE_SRGB 1  // sRGB views sample as linear light: encode back to display values

#define S3D_HOST_DEPTH_LINEAR 0  // R32F linear depth in world units (+inf or <= 0 as in the stereo pass)
#define S3D_HOST_DEPTH_DEVICE 1  // a hardware depth buffer, linearized with LinearDepthParams

// How the gather from a host's images reads its depth: the specialization constant its pipelines are made with.
#define S3D_HOST_GATHER_DEPTH_ONE_LAYER 0     // a depth buffer without a first-person range: taps compared as keys
#define S3D_HOST_GATHER_DEPTH_FIRST_PERSON 1  // with a first-person range: keys, or each tap near the weapon
#define S3D_HOST_GATHER_DEPTH_LINEAR 2        // R32F linear depth: read as it is

// Where the gather from a host's images (stereo_gather_host*.comp) writes, a specialization constant of its
// pipelines: the two eyes, or packed straight into one target (the half packings gather the pixels of one eye that
// a packed pixel filters).
#define S3D_HOST_GATHER_TWO_EYES 0
#define S3D_HOST_GATHER_ANAGLYPH 1
#define S3D_HOST_GATHER_SIDE_BY_SIDE_FULL 2
#define S3D_HOST_GATHER_TOP_BOTTOM_FULL 3
#define S3D_HOST_GATHER_SIDE_BY_SIDE_HALF 4
#define S3D_HOST_GATHER_TOP_BOTTOM_HALF 5

struct HostInputConstants {
  LinearDepthParams depth;
  int width;
  int height;
  int colorTransfer;
  int depthKind;
  int padding0;
  int padding1;
};

#define S3D_HOST_PACK_SIDE_BY_SIDE_HALF 0
#define S3D_HOST_PACK_SIDE_BY_SIDE_FULL 1
#define S3D_HOST_PACK_TOP_BOTTOM_HALF 2
#define S3D_HOST_PACK_TOP_BOTTOM_FULL 3
#define S3D_HOST_PACK_ANAGLYPH 4

struct HostPackConstants {
  int mode;
  int eyeWidth;
  int eyeHeight;
  int eyesEncoded;  // 1: the eyes hold sRGB-encoded display values (mix in linear light), 0: linear (HDR)
};

// Display value <-> linear light (IEC 61966-2-1), for the packing's filters and mixes.
S3D_INLINE float hostSrgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : pow((encoded + 0.055f) / 1.055f, 2.4f);
}
S3D_INLINE float hostLinearToSrgb(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Dubois' least-squares red-cyan anaglyph (ICASSP 2001) of two eyes in linear light, as output_formats.cpp; rows
// are output channels.
S3D_INLINE vec3 hostDuboisAnaglyph(vec3 l, vec3 r) {
  return vec3(dot(vec3(0.456f, 0.500f, 0.176f), l) + dot(vec3(-0.043f, -0.088f, -0.002f), r),
              dot(vec3(-0.040f, -0.038f, -0.016f), l) + dot(vec3(0.378f, 0.734f, -0.018f), r),
              dot(vec3(-0.015f, -0.021f, -0.005f), l) + dot(vec3(-0.072f, -0.113f, 1.226f), r));
}

S3D_GPU_END

#endif  // S3D_STEREO_HOST_PASS_SHARED_H
