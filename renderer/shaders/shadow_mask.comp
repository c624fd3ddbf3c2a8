#version 450
// Deferred sun shadow mask (seed 003 8.5.3.6, 000 4.3.3): per pixel, the world position from depth picks the
// first cascade that contains it (the one with the most texels per metre) and a PCF lookup gives the share of
// the sun that reaches it. The sun term of the light pass is scaled by it; ambient is not.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform sampler2D normalGlossiness;
layout(binding = 3) uniform sampler2DShadow sunAtlas;  // compare LESS_OR_EQUAL, bilinear: 2x2 PCF per tap
layout(binding = 4) uniform Shadows { ShadowConstants shadow; };
layout(binding = 5, r16f) uniform writeonly image2D shadowMask;

// 2x2 bilinear compare taps half a texel off the centre: a tent-weighted 3x3-texel percentage-closer filter
// (16 texel compares; a 3x3 grid of taps, 36 compares, cost lavapipe twice the time for a softer edge).
float sunPcf(int cascade, vec2 uv, float receiverDepth) {
  vec4 rect = shadow.cascadeAtlasRect[cascade];
  vec2 texel = shadow.sunShadow.yz;
  vec2 atlasUv = rect.xy + uv * rect.zw;
  float lit = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      lit += textureLod(sunAtlas, vec3(atlasUv + (vec2(x, y) - 0.5) * texel, receiverDepth), 0.0);
  return lit * 0.25;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.screen.x) || pixel.y >= int(frame.screen.y)) return;
  float depth = texelFetch(deviceDepth, pixel, 0).r;
  if (isSkyDeviceDepth(frame.linearDepth, depth)) {
    imageStore(shadowMask, pixel, vec4(1.0));
    return;
  }
  // World position as in the light pass (Listing 4.3, then the layer's projection).
  uint layer = isFirstPersonDeviceDepth(frame.linearDepth, depth) ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
  float linearDepth = linearDepthFromDepthBuffer(frame.linearDepth, depth);
  vec2 ndc = (vec2(pixel) + 0.5) * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[layer].projection;
  vec3 viewPosition = vec3((ndc.x + p.z) * linearDepth / p.x, (ndc.y + p.w) * linearDepth / p.y, -linearDepth);
  vec3 worldPosition = (frame.layers[layer].worldFromView * vec4(viewPosition, 1.0)).xyz;
  vec3 normal = normalize(texelFetch(normalGlossiness, pixel, 0).xyz);
  if (dot(normal, frame.directionToSun.xyz) <= 0.0) {
    imageStore(shadowMask, pixel, vec4(0.0));  // faces away from the sun: self-shadowed, no lookup needed
    return;
  }

  float lit = 1.0;  // beyond the last cascade: unshadowed
  int count = int(shadow.sunShadow.x);
  for (int cascade = 0; cascade < count; ++cascade) {
    vec4 params = shadow.cascadeParams[cascade];
    // Normal offset of one texel against acne where the surface turns away from the sun.
    vec3 receiver = worldPosition + normal * params.x;
    vec3 clip = (shadow.cascadeViewProjection[cascade] * vec4(receiver, 1.0)).xyz;  // orthographic: w = 1
    vec2 uv = clip.xy * 0.5 + 0.5;
    vec2 margin = 2.0 * shadow.sunShadow.yz / shadow.cascadeAtlasRect[cascade].zw;  // the PCF footprint stays inside
    if (any(lessThan(uv, margin)) || any(greaterThan(uv, 1.0 - margin)) || clip.z > 1.0) continue;
    if (params.y > 0.5) lit = sunPcf(cascade, uv, clip.z - params.z);
    break;  // a cascade without casters leaves the point lit
  }
  imageStore(shadowMask, pixel, vec4(lit));
}
