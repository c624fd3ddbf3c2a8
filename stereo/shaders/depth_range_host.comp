#version 450
// The frame's depth range (depth_range.h) of a host's depth buffer as it is (D32, D24S8, D16: each texel
// linearized as the stereo pass linearizes it, the first-person layer pushed; or R32F linear depth), sampled.
#extension GL_GOOGLE_include_directive : require
#include "s3d/gpu/linear_depth.h"

layout(binding = 0) uniform sampler2D hostDepth;
layout(push_constant) uniform Push {
  LinearDepthParams depthParams;
  int deviceDepth;  // 1: hardware depth to linearize; 0: linear depth
};
float hostStereoDepth(ivec2 texel) {
  float depth = texelFetch(hostDepth, texel, 0).r;
  return deviceDepth != 0 ? stereoDepthFromDevice(depthParams, depth) : depth;
}
#define S3D_DEPTH_AT(texel) hostStereoDepth(texel)
#define S3D_DEPTH_SIZE() textureSize(hostDepth, 0)
#include "depth_range.glsl"
