#version 450
// Device depth -> the stereo pass's linear depth in world units (Listing 4.3; +inf for sky; weapon pushed).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2, r32f) uniform writeonly image2D linearDepth;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.screen.x) || pixel.y >= int(frame.screen.y)) return;
  float depth = texelFetch(deviceDepth, pixel, 0).r;
  imageStore(linearDepth, pixel, vec4(stereoDepthFromDevice(frame.linearDepth, depth)));
}
