// Listing 4.5 as a compute pass (and its N-tap search): one invocation writes the pixel of both eyes.
// Included by stereo_seed.comp and stereo_search.comp, which set S3D_STEREO_TAP_CAPACITY first. With
// S3D_STEREO_HOST_INPUTS (stereo_gather_host*.comp) it reads a host's colour and depth buffer as they are, sampled,
// converting each texel as the host pass's input conversion would (host_input.glsl), so no conversion pass runs.
#include "s3d/stereo/stereo_shared.h"
#ifdef S3D_STEREO_HOST_INPUTS
#include "s3d/stereo/host_pass_shared.h"
#endif

// The colour images' format: display RGBA8, or rgba16f for a host's HDR colour (stereo_*_hdr.comp).
#ifndef S3D_STEREO_COLOR_FORMAT
#define S3D_STEREO_COLOR_FORMAT rgba8
#endif

layout(local_size_x = S3D_STEREO_GROUP_SIZE, local_size_y = S3D_STEREO_GROUP_SIZE) in;

#ifdef S3D_STEREO_HOST_INPUTS
layout(binding = 0) uniform sampler2D hostColor;
layout(binding = 1) uniform sampler2D hostDepth;
#else
layout(binding = 0, S3D_STEREO_COLOR_FORMAT) uniform readonly image2D centerColor;
layout(binding = 1, r32f) uniform readonly image2D linearDepth;
#endif
layout(binding = 2, S3D_STEREO_COLOR_FORMAT) uniform writeonly image2D leftEye;
layout(binding = 3, S3D_STEREO_COLOR_FORMAT) uniform writeonly image2D rightEye;

layout(push_constant) uniform Push {
  StereoConstants c;
#ifdef S3D_STEREO_HOST_INPUTS
  HostInputConstants h;  // right after the short tap array (HostGatherConstants in C++)
#endif
};

float depthAt(int x, int y) {
  ivec2 texel = ivec2(clamp(x, 0, c.width - 1), y);
#ifdef S3D_STEREO_HOST_INPUTS
  float depth = texelFetch(hostDepth, texel, 0).r;
  if (h.depthKind == S3D_HOST_DEPTH_DEVICE) depth = stereoDepthFromDevice(h.depth, depth);
#else
  float depth = imageLoad(linearDepth, texel).r;
#endif
  return sanitizedDepth(depth, c.zeroParallaxDistance);
}

vec4 centerAt(int x, int y) {
  ivec2 texel = ivec2(clamp(x, 0, c.width - 1), y);
#ifdef S3D_STEREO_HOST_INPUTS
  vec4 color = texelFetch(hostColor, texel, 0);
  if (h.colorTransfer == S3D_HOST_COLOR_ENCODE_SRGB)
    color.rgb = vec3(hostLinearToSrgb(color.r), hostLinearToSrgb(color.g), hostLinearToSrgb(color.b));
  return color;
#else
  return imageLoad(centerColor, texel);
#endif
}

#ifdef S3D_STEREO_HOST_INPUTS
// Listing 4.5 on a host's depth buffer of one layer (no first-person depth range): its stereo depth never
// decreases with the device depth's key (linear_depth.h), so the taps' minimum is taken in keys and converted
// once instead of per tap. Out-of-range and NaN taps read as the zero-parallax plane, as their conversion does.
float minDepthOverOneLayersTaps(int x, int y, int direction) {
  float nearestKey = S3D_INFINITY;
  bool outOfRange = false;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i) {
    if (i >= c.tapCount) continue;
    ivec2 texel = ivec2(clamp(x + direction * c.tapOffsetPx[i], 0, c.width - 1), y);
    float key = deviceDepthKey(h.depth, texelFetch(hostDepth, texel, 0).r);
    bool inRange = isDeviceDepthKeyInRange(h.depth, key);
    outOfRange = outOfRange || !inRange;
    nearestKey = inRange ? min(nearestKey, key) : nearestKey;
  }
  float minDepth = outOfRange ? c.zeroParallaxDistance : S3D_INFINITY;
  if (nearestKey == S3D_INFINITY) return minDepth;  // no tap in range, or the sky at +inf
  float deviceDepth = deviceDepthKey(h.depth, nearestKey);  // the key's negation is its own inverse
  return min(minDepth, sanitizedDepth(stereoDepthFromDevice(h.depth, deviceDepth), c.zeroParallaxDistance));
}
#endif

#define S3D_GATHER_TAP_COUNT c.tapCount
#define S3D_GATHER_TAP_OFFSET_PX c.tapOffsetPx
#include "stereo_gather_source.glsl"

// The taps' nearest depth on one side of the pixel: from a host's one-layer depth buffer in keys, else per tap.
float nearestTapDepth(int x, int y, int direction) {
#ifdef S3D_STEREO_HOST_INPUTS
  if (h.depthKind == S3D_HOST_DEPTH_DEVICE && hasNoFirstPersonLayer(h.depth)) return minDepthOverOneLayersTaps(x, y, direction);
#endif
  return minDepthOverTaps(x, y, direction);
}

// Both eyes' pixel: stored in the two eyes, or (from host images) packed straight into the target at binding 2.
void writeEyes(ivec2 pixel, vec4 left, vec4 right) {
#ifdef S3D_STEREO_HOST_INPUTS
  if (h.gatherOutput == S3D_HOST_GATHER_ANAGLYPH) {  // 8-bit eyes: mixed from their stored bytes, as the packing pass
    const float byteScale = 1.0 / 255.0;
    vec3 l = round(clamp(left.rgb, 0.0, 1.0) * 255.0) * byteScale, r = round(clamp(right.rgb, 0.0, 1.0) * 255.0) * byteScale;
    l = vec3(hostSrgbToLinear(l.r), hostSrgbToLinear(l.g), hostSrgbToLinear(l.b));
    r = vec3(hostSrgbToLinear(r.r), hostSrgbToLinear(r.g), hostSrgbToLinear(r.b));
    vec3 mixed = clamp(hostDuboisAnaglyph(l, r), 0.0, 1.0);
    imageStore(leftEye, pixel, vec4(hostLinearToSrgb(mixed.r), hostLinearToSrgb(mixed.g), hostLinearToSrgb(mixed.b), 1.0));
    return;
  }
  if (h.gatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL || h.gatherOutput == S3D_HOST_GATHER_TOP_BOTTOM_FULL) {
    imageStore(leftEye, pixel, left);
    imageStore(leftEye, pixel + (h.gatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL ? ivec2(c.width, 0) : ivec2(0, c.height)),
               right);
    return;
  }
#endif
  imageStore(leftEye, pixel, left);
  imageStore(rightEye, pixel, right);
}

// Horizontal linear filter at texel coordinate u (texel centers at integers), clamped to the edge.
vec4 sampleRow(int y, float u) {
  float base = floor(u);
  float fraction = u - base;
  vec4 a = centerAt(int(base), y);
  vec4 b = centerAt(int(base) + 1, y);
  return a * (1.0 - fraction) + b * fraction;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges
    writeEyes(pixel, vec4(0, 0, 0, 1), vec4(0, 0, 0, 1));
    return;
  }
  writeEyes(pixel, sampleRow(pixel.y, gatherSourceColumn(pixel.x, +1, nearestTapDepth(pixel.x, pixel.y, +1))),
            sampleRow(pixel.y, gatherSourceColumn(pixel.x, -1, nearestTapDepth(pixel.x, pixel.y, -1))));
}
