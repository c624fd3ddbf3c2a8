#version 450
// The resolve, one dispatch over the output (tone map and linear depth read the same samples, so one pass):
// HDR -> display (exposure, a filmic curve, then sRGB encoding; linear space until here) and device depth ->
// the stereo pass's linear depth in world units (Listing 4.3; +inf for sky; weapon pushed). With
// supersampling, the samples of an output pixel are averaged after the tone curve (a bright sample cannot swamp
// the pixel) and before sRGB encoding (averaging stays linear); the depth is the nearest sample's, so the
// stereo pass moves a partly covered pixel with its occluder, as Listing 4.5's minimum-depth search does.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1, rgba16f) uniform readonly image2D hdrColor;
layout(binding = 2, rgba8) uniform writeonly image2D displayColor;
layout(binding = 3, rgba16f) uniform writeonly image2D resolvedHdrColor;
layout(binding = 4) uniform sampler2D deviceDepth;
layout(binding = 5, r32f) uniform writeonly image2D linearDepth;
layout(push_constant) uniform Push { ResolveConstants resolve; };

// Krzysztof Narkowicz's fit of the ACES filmic tone curve (2016).
vec3 filmic(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

vec3 encodeSrgb(vec3 linear) {
  return mix(linear * 12.92, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), linear));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= resolve.outputWidth || pixel.y >= resolve.outputHeight) return;
  vec4 hdrSum = vec4(0.0);
  vec3 toneMappedSum = vec3(0.0);
  float weapon = 0.0;
  float nearestDepth = S3D_INFINITY;
  float nearestDevice = texelFetch(deviceDepth, pixel * resolve.supersample, 0).r;
  for (int sy = 0; sy < resolve.supersample; ++sy)
    for (int sx = 0; sx < resolve.supersample; ++sx) {
      ivec2 sampleTexel = pixel * resolve.supersample + ivec2(sx, sy);
      vec4 hdr = imageLoad(hdrColor, sampleTexel);
      // NaN or inf (a broken shader or input) is black, as stereo::sanitizeColor makes it: the curve would turn
      // it into NaN and the unorm store into an undefined level that the stereo pass would then displace.
      if (any(isnan(hdr)) || any(isinf(hdr))) hdr = vec4(0.0);
      hdrSum += hdr;
      toneMappedSum += filmic(hdr.rgb * frame.exposure.x);
      float device = texelFetch(deviceDepth, sampleTexel, 0).r;
      // A pixel any of whose samples is first-person is a weapon pixel (its linear depth is the weapon's too).
      if (isFirstPersonDeviceDepth(frame.linearDepth, device)) weapon = 1.0;
      float depth = linearDepthFromDepthBuffer(frame.linearDepth, device);  // nearest by true depth, before the push
      if (depth < nearestDepth) {
        nearestDepth = depth;
        nearestDevice = device;
      }
    }
  float sampleCount = float(resolve.supersample * resolve.supersample);
  // Seed 4.6.2: the weapon mask rides in alpha (0 on the first-person layer, 1 elsewhere); the stereo pass
  // carries it into both eyes, where HUD elements behind the weapon fade out (s3d/hud/overlay.h).
  imageStore(displayColor, pixel, vec4(encodeSrgb(toneMappedSum / sampleCount), 1.0 - weapon));
  imageStore(resolvedHdrColor, pixel, hdrSum / sampleCount);
  imageStore(linearDepth, pixel, vec4(stereoDepthFromDevice(frame.linearDepth, nearestDevice)));
}
