// The host pass's input conversion: the host's colour (any sampled format) and depth (hardware depth or linear)
// become the stereo kernel's display colour and linear depth. Included with S3D_HOST_COLOR_FORMAT set.
#include "s3d/stereo/host_pass_shared.h"

layout(local_size_x = S3D_HOST_GROUP_SIZE, local_size_y = S3D_HOST_GROUP_SIZE) in;
layout(binding = 0) uniform sampler2D hostColor;
layout(binding = 1) uniform sampler2D hostDepth;
layout(binding = 2, S3D_HOST_COLOR_FORMAT) uniform writeonly image2D centerColor;
layout(binding = 3, r32f) uniform writeonly image2D linearDepth;
layout(push_constant) uniform Push { HostInputConstants c; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  vec4 color = texelFetch(hostColor, pixel, 0);
  if (c.colorTransfer == S3D_HOST_COLOR_ENCODE_SRGB)
    color.rgb = vec3(hostLinearToSrgb(color.r), hostLinearToSrgb(color.g), hostLinearToSrgb(color.b));
  imageStore(centerColor, pixel, color);
  float depth = texelFetch(hostDepth, pixel, 0).r;
  if (c.depthKind == S3D_HOST_DEPTH_DEVICE) depth = stereoDepthFromDevice(c.depth, depth);
  imageStore(linearDepth, pixel, vec4(depth));
}
