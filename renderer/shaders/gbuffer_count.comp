#version 450
// Counting renders only (tests): the render pixels the G-buffer wrote, told by an object index.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
#define S3D_TILES_BINDING 1
#include "tiles.glsl"
layout(binding = 2) uniform usampler2D material;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.screen.xy)))) return;
  if (unpackObjectIndex(texelFetch(material, pixel, 0).rg) != S3D_NO_OBJECT) countShaded(S3D_COUNT_GBUFFER, 1u);
}
