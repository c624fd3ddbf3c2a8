#version 450
// Screen-space ambient occlusion (world layer) at half resolution: per texel (the render pixel 2i, 2j), the
// share of a normal-oriented hemisphere of sample points around the surface point that the depth buffer shows
// to be behind a nearer surface. The normal comes from the depth buffer (neighbours on the smoother side), so
// the pass needs depth only: a masked render gives it every pixel's depth (its G-buffer's or a depth-only pass's). Writes
// the occlusion and the texel's linear depth (+inf for sky and weapon) for the depth-aware blur and upsample.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2, rg16f) uniform writeonly image2D ambientOcclusion;
#define S3D_TILES_BINDING 3
#include "tiles.glsl"

// View-space position of a pixel of the world layer from its linear depth (Listing 4.3, off-axis aware). The
// pass works in the world layer's view space: its projection is then four terms, not a matrix.
vec3 viewPositionAt(vec2 pixelCenter, float linearDepth) {
  vec2 ndc = pixelCenter * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[S3D_LAYER_WORLD].projection;
  return vec3((ndc.x + p.z) * linearDepth / p.x, (ndc.y + p.w) * linearDepth / p.y, -linearDepth);
}

bool isWorldSurface(float device) {
  return !isSkyDeviceDepth(frame.linearDepth, device) && !isFirstPersonDeviceDepth(frame.linearDepth, device);
}

// The surface step to a neighbour pixel (offset +-1 along one axis), or none (sky, weapon, off screen): w = 0.
vec4 stepTo(ivec2 pixel, ivec2 offset, vec3 position, float linearDepth) {
  ivec2 neighbour = pixel + offset;
  if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, ivec2(frame.screen.xy)))) return vec4(0.0);
  float device = texelFetch(deviceDepth, neighbour, 0).r;
  if (!isWorldSurface(device)) return vec4(0.0);
  float depth = linearDepthFromDepthBuffer(frame.linearDepth, device);
  return vec4(viewPositionAt(vec2(neighbour) + 0.5, depth) - position, 1.0 / (1e-6 + abs(depth - linearDepth)));
}

// Of the two neighbours along an axis, the step to the one nearer in depth (the same surface more likely);
// `forward` says which it was, so both axes' steps can be oriented alike.
vec3 smootherStep(ivec2 pixel, ivec2 axis, vec3 position, float linearDepth) {
  vec4 after = stepTo(pixel, axis, position, linearDepth);
  vec4 before = stepTo(pixel, -axis, position, linearDepth);
  if (after.w == 0.0 && before.w == 0.0) return vec3(0.0);
  return after.w >= before.w ? after.xyz : -before.xyz;
}

void main() {
  ivec2 texel = ambientTile() * S3D_COMPUTE_GROUP_SIZE + ivec2(gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(frame.ambientOcclusion.yz)))) return;
  countShaded(S3D_COUNT_SSAO, 1u);
  ivec2 pixel = min(texel * 2, ivec2(frame.screen.xy) - 1);
  float depth = texelFetch(deviceDepth, pixel, 0).r;
  if (!isWorldSurface(depth)) {
    imageStore(ambientOcclusion, texel, vec4(1.0, S3D_INFINITY, 0.0, 0.0));  // sky and weapon: unoccluded
    return;
  }
  float linearDepth = linearDepthFromDepthBuffer(frame.linearDepth, depth);
  vec3 position = viewPositionAt(vec2(pixel) + 0.5, linearDepth);
  vec3 normal = cross(smootherStep(pixel, ivec2(1, 0), position, linearDepth),
                      smootherStep(pixel, ivec2(0, 1), position, linearDepth));
  normal = dot(normal, normal) > 0.0 ? normalize(normal) : normalize(-position);  // an isolated pixel faces the eye
  if (dot(normal, position) > 0.0) normal = -normal;
  // A tangent frame around the normal; the kernel turns by a per-texel angle (4x4 pattern, which the blur
  // averages out exactly) against banding.
  vec3 helper = abs(normal.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = normalize(cross(helper, normal));
  vec3 bitangent = cross(normal, tangent);
  float turn = float((texel.x & 3) * 4 + (texel.y & 3)) * (6.2831853 / 16.0);
  float radius = frame.ambientOcclusion.x;
  vec4 p = frame.layers[S3D_LAYER_WORLD].projection;
  float occluded = 0.0;
  for (int i = 0; i < S3D_SSAO_SAMPLES; ++i) {
    // Golden-angle spiral over the hemisphere, denser near the surface point.
    float t = (float(i) + 0.5) / float(S3D_SSAO_SAMPLES);
    float angle = float(i) * 2.3999632 + turn;
    float elevation = sqrt(1.0 - t);
    vec3 direction = tangent * (cos(angle) * sqrt(t)) + bitangent * (sin(angle) * sqrt(t)) + normal * elevation;
    vec3 samplePoint = position + direction * (radius * mix(0.2, 1.0, t * t));
    float sampleLinear = -samplePoint.z;  // view depth of the sample point
    if (sampleLinear <= 0.0) continue;
    vec2 ndc = vec2(p.x * samplePoint.x, p.y * samplePoint.y) / sampleLinear - p.zw;
    vec2 samplePixel = (ndc * 0.5 + 0.5) * frame.screen.xy;
    if (any(lessThan(samplePixel, vec2(0.0))) || any(greaterThanEqual(samplePixel, frame.screen.xy))) continue;
    float sceneDepth = texelFetch(deviceDepth, ivec2(samplePixel), 0).r;
    if (!isWorldSurface(sceneDepth)) continue;
    float sceneLinear = linearDepthFromDepthBuffer(frame.linearDepth, sceneDepth);
    // Occluded when a surface lies in front of the sample, but not one far in front (a range check).
    float inFront = sampleLinear - sceneLinear;
    if (inFront > 0.02 * radius && inFront < radius) occluded += 1.0;
  }
  imageStore(ambientOcclusion, texel, vec4(1.0 - occluded / float(S3D_SSAO_SAMPLES), linearDepth, 0.0, 0.0));
}
