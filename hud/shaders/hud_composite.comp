#version 450
// One HUD element layer over both eyes (z = 0 left, 1 right) at its eye origins, with the C++ reference's per-pixel
// math (hud_pass_shared.h): 8-bit levels as floats, opacity faded by the weapon mask in the eye's alpha, rounded.
#extension GL_GOOGLE_include_directive : require
#include "s3d/hud/hud_pass_shared.h"

layout(local_size_x = S3D_HUD_GROUP_SIZE, local_size_y = S3D_HUD_GROUP_SIZE) in;
layout(binding = 0) uniform sampler2D layer;  // straight-alpha RGBA8 (BGRA8 views read in RGBA order)
layout(binding = 1, rgba8) uniform image2D leftEye;
layout(binding = 2, rgba8) uniform image2D rightEye;
layout(push_constant) uniform Push { HudCompositeConstants c; };

vec4 levels(vec4 unorm) { return roundEven(unorm * 255.0); }  // UNORM reads are exact multiples of 1/255

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  bool left = gl_GlobalInvocationID.z == 0u;
  if (texel.x >= c.layerWidth || texel.y >= c.layerHeight) return;
  ivec2 pixel = texel + (left ? ivec2(c.leftOriginX, c.leftOriginY) : ivec2(c.rightOriginX, c.rightOriginY));
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= c.eyeWidth || pixel.y >= c.eyeHeight) return;
  vec4 source = levels(texelFetch(layer, texel, 0));
  if (source.a == 0.0) return;
  vec4 target = levels(left ? imageLoad(leftEye, pixel) : imageLoad(rightEye, pixel));
  float opacity = hudOpacity(source.a, target.a, c.behindWeapon);
  if (opacity <= 0.0) return;
  vec3 blended = vec3(hudBlendChannel(target.r, source.r, opacity), hudBlendChannel(target.g, source.g, opacity),
                      hudBlendChannel(target.b, source.b, opacity));
  vec4 result = vec4(blended, target.a) / 255.0;
  if (left) imageStore(leftEye, pixel, result);
  else imageStore(rightEye, pixel, result);
}
