#version 450
// The resolve, one dispatch over the output (tone map and linear depth read the same samples, so one pass):
// HDR -> display (exposure, a filmic curve, then sRGB encoding; linear space until here) and device depth ->
// the stereo pass's linear depth in world units (Listing 4.3; +inf for sky; weapon pushed). With
// supersampling, the samples of an output pixel are averaged after the tone curve (a bright sample cannot swamp
// the pixel) and before sRGB encoding (averaging stays linear); the depth is the nearest sample's, so the
// stereo pass moves a partly covered pixel with its occluder, as Listing 4.5's minimum-depth search does.
// One thread per output pixel. A masked render runs one workgroup per listed render tile, over the output
// pixels whose first sample lies in it, and resolves only shade-mask pixels.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "tonemap.glsl"

layout(local_size_x = S3D_TILE_SIZE, local_size_y = S3D_TILE_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1, rgba16f) uniform readonly image2D hdrColor;
layout(binding = 2, rgba8) uniform writeonly image2D displayColor;
layout(binding = 3, rgba16f) uniform writeonly image2D resolvedHdrColor;
layout(binding = 4) uniform sampler2D deviceDepth;
layout(binding = 5, r32f) uniform writeonly image2D linearDepth;
layout(push_constant) uniform Push { ResolveConstants resolve; };
#define S3D_TILES_BINDING 6
#define S3D_SHADE_MASK_BINDING 7
#include "tiles.glsl"

void resolvePixel(ivec2 pixel) {
  vec4 hdrSum = vec4(0.0);
  vec3 toneMappedSum = vec3(0.0);
  float weapon = 0.0;
  float nearestDepth = S3D_INFINITY;
  float nearestDevice = texelFetch(deviceDepth, pixel * resolve.supersample, 0).r;
  for (int sy = 0; sy < resolve.supersample; ++sy)
    for (int sx = 0; sx < resolve.supersample; ++sx) {
      ivec2 sampleTexel = pixel * resolve.supersample + ivec2(sx, sy);
      vec4 hdr = finiteHdr(imageLoad(hdrColor, sampleTexel));
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

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 end = ivec2(resolve.outputWidth, resolve.outputHeight);
  if (maskedRender()) {
    // The output pixels o with o * supersample inside the render tile: [ceil(start / s), ceil(end / s)).
    ivec2 tile = maskedTile();
    int s = resolve.supersample;
    pixel = (tile * S3D_TILE_SIZE + s - 1) / s + ivec2(gl_LocalInvocationID.xy);
    end = min((tile * S3D_TILE_SIZE + S3D_TILE_SIZE + s - 1) / s, end);
  }
  if (any(greaterThanEqual(pixel, end)) || !shadeMasked(pixel * resolve.supersample)) return;
  resolvePixel(pixel);
  countShaded(S3D_COUNT_RESOLVE, 1u);
}
