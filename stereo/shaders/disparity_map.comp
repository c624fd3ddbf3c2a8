#version 450
// The nonlinear depth-to-parallax mapping (disparity_map_shared.h), in place on the stereo pass's linear depth.
#extension GL_GOOGLE_include_directive : require
#include "s3d/stereo/disparity_map_shared.h"

layout(local_size_x = S3D_DISPARITY_MAP_GROUP_SIZE, local_size_y = S3D_DISPARITY_MAP_GROUP_SIZE) in;
layout(binding = 0, r32f) uniform image2D linearDepth;
layout(push_constant) uniform Constants { DisparityMapConstants map; };

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(linearDepth)))) return;
  imageStore(linearDepth, pixel, vec4(mappedDepth(map, imageLoad(linearDepth, pixel).r)));
}
