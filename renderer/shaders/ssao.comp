#version 450
// Screen-space ambient occlusion (world layer): the share of a normal-oriented hemisphere of sample points
// around each surface point that the depth buffer shows to be behind a nearer surface. Applied to the
// ambient light only, in the sun-and-ambient pass.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform sampler2D normalGlossiness;
layout(binding = 3, r16f) uniform writeonly image2D ambientOcclusion;

// World position of a pixel of the world layer from its device depth (as in the light pass).
vec3 worldPositionAt(vec2 pixelCenter, float depth) {
  float linearDepth = linearDepthFromDepthBuffer(frame.linearDepth, depth);
  vec2 ndc = pixelCenter * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[S3D_LAYER_WORLD].projection;
  vec3 viewPosition = vec3((ndc.x + p.z) * linearDepth / p.x, (ndc.y + p.w) * linearDepth / p.y, -linearDepth);
  return (frame.layers[S3D_LAYER_WORLD].worldFromView * vec4(viewPosition, 1.0)).xyz;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= int(frame.screen.x) || pixel.y >= int(frame.screen.y)) return;
  float depth = texelFetch(deviceDepth, pixel, 0).r;
  if (isSkyDeviceDepth(frame.linearDepth, depth) || isFirstPersonDeviceDepth(frame.linearDepth, depth)) {
    imageStore(ambientOcclusion, pixel, vec4(1.0));  // sky and weapon: unoccluded
    return;
  }
  vec3 position = worldPositionAt(vec2(pixel) + 0.5, depth);
  vec3 normal = normalize(texelFetch(normalGlossiness, pixel, 0).xyz);
  // A tangent frame around the normal; the kernel turns by a per-pixel angle (4x4 pattern) against banding.
  vec3 helper = abs(normal.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = normalize(cross(helper, normal));
  vec3 bitangent = cross(normal, tangent);
  float turn = float((pixel.x & 3) * 4 + (pixel.y & 3)) * (6.2831853 / 16.0);
  float radius = frame.ambientOcclusion.x;
  mat4 viewProjection = frame.layers[S3D_LAYER_WORLD].viewProjection;
  float occluded = 0.0;
  for (int i = 0; i < S3D_SSAO_SAMPLES; ++i) {
    // Golden-angle spiral over the hemisphere, denser near the surface point.
    float t = (float(i) + 0.5) / float(S3D_SSAO_SAMPLES);
    float angle = float(i) * 2.3999632 + turn;
    float elevation = sqrt(1.0 - t);
    vec3 direction = tangent * (cos(angle) * sqrt(t)) + bitangent * (sin(angle) * sqrt(t)) + normal * elevation;
    vec3 samplePoint = position + direction * (radius * mix(0.2, 1.0, t * t));
    vec4 clip = viewProjection * vec4(samplePoint, 1.0);
    if (clip.w <= 0.0) continue;
    vec2 samplePixel = (clip.xy / clip.w * 0.5 + 0.5) * frame.screen.xy;
    if (any(lessThan(samplePixel, vec2(0.0))) || any(greaterThanEqual(samplePixel, frame.screen.xy))) continue;
    float sceneDepth = texelFetch(deviceDepth, ivec2(samplePixel), 0).r;
    if (isSkyDeviceDepth(frame.linearDepth, sceneDepth) || isFirstPersonDeviceDepth(frame.linearDepth, sceneDepth)) continue;
    float sceneLinear = linearDepthFromDepthBuffer(frame.linearDepth, sceneDepth);
    float sampleLinear = clip.w;  // view depth of the sample point
    // Occluded when a surface lies in front of the sample, but not one far in front (a range check).
    float inFront = sampleLinear - sceneLinear;
    if (inFront > 0.02 * radius && inFront < radius) occluded += 1.0;
  }
  imageStore(ambientOcclusion, pixel, vec4(1.0 - occluded / float(S3D_SSAO_SAMPLES)));
}
