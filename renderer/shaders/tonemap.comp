#version 450
// HDR -> display: exposure, a filmic curve, then sRGB encoding (linear space until here).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1, rgba16f) uniform readonly image2D hdrColor;
layout(binding = 2, rgba8) uniform writeonly image2D displayColor;
layout(binding = 3) uniform sampler2D deviceDepth;

// Krzysztof Narkowicz's fit of the ACES filmic tone curve (2016).
vec3 filmic(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

vec3 encodeSrgb(vec3 linear) {
  return mix(linear * 12.92, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), linear));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.screen.x) || pixel.y >= int(frame.screen.y)) return;
  vec3 hdr = imageLoad(hdrColor, pixel).rgb * frame.exposure.x;
  // Seed 4.6.2: the weapon mask rides in alpha (0 on the first-person layer, 1 elsewhere); the stereo pass
  // carries it into both eyes, where HUD elements behind the weapon fade out (s3d/hud/overlay.h).
  float weapon = step(texelFetch(deviceDepth, pixel, 0).r, frame.linearDepth.firstPersonDeviceDepthMax);
  imageStore(displayColor, pixel, vec4(encodeSrgb(filmic(hdr)), 1.0 - weapon));
}
