#version 450
// Device depth -> the stereo pass's linear depth in world units (Listing 4.3; +inf for sky; weapon pushed).
// With supersampling, the nearest sample's depth: the stereo pass moves a partly covered pixel with its
// occluder, as Listing 4.5's minimum-depth search does.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2, r32f) uniform writeonly image2D linearDepth;
layout(push_constant) uniform Push { ResolveConstants resolve; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= resolve.outputWidth || pixel.y >= resolve.outputHeight) return;
  float nearestDepth = S3D_INFINITY;
  float nearestDevice = texelFetch(deviceDepth, pixel * resolve.supersample, 0).r;
  for (int sy = 0; sy < resolve.supersample; ++sy)
    for (int sx = 0; sx < resolve.supersample; ++sx) {
      float device = texelFetch(deviceDepth, pixel * resolve.supersample + ivec2(sx, sy), 0).r;
      float depth = linearDepthFromDepthBuffer(frame.linearDepth, device);  // nearest by true depth, before the push
      if (depth < nearestDepth) {
        nearestDepth = depth;
        nearestDevice = device;
      }
    }
  imageStore(linearDepth, pixel, vec4(stereoDepthFromDevice(frame.linearDepth, nearestDevice)));
}
