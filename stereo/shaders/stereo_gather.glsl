// Listing 4.5 as a compute pass (and its N-tap search): one invocation writes the pixel of both eyes.
// Included by stereo_seed.comp and stereo_search.comp, which set S3D_STEREO_TAP_CAPACITY first. With
// S3D_STEREO_BASE_DEPTH_OUTPUT (stereo_*_base_depth.comp) it also writes the hybrid's base depth: per eye pixel the
// center's device depth at the texel nearest its source column, as stereo_hybrid_base_depth.comp does, the source
// columns found once for both outputs. With
// S3D_STEREO_HOST_INPUTS (stereo_gather_host*.comp) it reads a host's colour and depth buffer as they are, sampled,
// converting each texel as the host pass's input conversion would (host_input.glsl), so no conversion pass runs;
// with S3D_STEREO_HOST_HALF_PACKING too, each invocation writes one pixel of a half packing instead.
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
#ifdef S3D_STEREO_BASE_DEPTH_OUTPUT
layout(binding = 4) uniform sampler2D deviceDepth;  // the center's (a depth attachment: sampled, not storage)
layout(binding = 5, r32f) uniform writeonly image2D leftBaseDepth;
layout(binding = 6, r32f) uniform writeonly image2D rightBaseDepth;
#endif

layout(push_constant) uniform Push {
  StereoConstants c;
#ifdef S3D_STEREO_HOST_INPUTS
  HostInputConstants h;  // right after the short tap array (HostGatherConstants in C++)
#endif
};
#ifdef S3D_STEREO_HOST_INPUTS
// How the host's depth reads (S3D_HOST_GATHER_DEPTH_*), where the gather writes (S3D_HOST_GATHER_*) and the colour's
// transfer, fixed when the pipeline is made: each pipeline compiles only its own paths (the unused ones behind
// per-frame branches slowed the gather: docs/RESULTS.md "Every input format").
layout(constant_id = 0) const int kHostDepthPath = S3D_HOST_GATHER_DEPTH_ONE_LAYER;
layout(constant_id = 1) const int kGatherOutput = S3D_HOST_GATHER_TWO_EYES;
layout(constant_id = 2) const int kColorTransfer = S3D_HOST_COLOR_AS_STORED;
#endif

float depthAt(int x, int y) {
  ivec2 texel = ivec2(clamp(x, 0, c.width - 1), y);
#ifdef S3D_STEREO_HOST_INPUTS
  float depth = texelFetch(hostDepth, texel, 0).r;  // linear R32F: a depth buffer's taps go through tapKeys
#else
  float depth = imageLoad(linearDepth, texel).r;
#endif
  return sanitizedDepth(depth, c.zeroParallaxDistance);
}

vec4 centerAt(int x, int y) {
  ivec2 texel = ivec2(clamp(x, 0, c.width - 1), y);
#ifdef S3D_STEREO_HOST_INPUTS
  vec4 color = texelFetch(hostColor, texel, 0);
  if (kColorTransfer == S3D_HOST_COLOR_ENCODE_SRGB)
    color.rgb = vec3(hostLinearToSrgb(color.r), hostLinearToSrgb(color.g), hostLinearToSrgb(color.b));
  return color;
#else
  return imageLoad(centerColor, texel);
#endif
}

#ifdef S3D_STEREO_HOST_INPUTS
// The device-depth keys (linear_depth.h) of the taps on one side of the pixel, unused taps +inf: every tap read
// before any is compared, so the reads overlap (comparing each tap as it was read was slower: docs/RESULTS.md
// "Where the host frame's extra time goes").
void tapKeys(int x, int y, int direction, out float keys[S3D_STEREO_TAP_CAPACITY]) {
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i) {
    keys[i] = S3D_INFINITY;
    if (i >= c.tapCount) continue;
    ivec2 texel = ivec2(clamp(x + direction * c.tapOffsetPx[i], 0, c.width - 1), y);
    keys[i] = deviceDepthKey(h.depth, texelFetch(hostDepth, texel, 0).r);
  }
}

// Listing 4.5 over taps of one layer (the world): its stereo depth never decreases with the device depth's key, so
// the taps' minimum is taken in keys and converted once instead of per tap. Out-of-range and NaN taps read as the
// zero-parallax plane, as their conversion does.
float minDepthOverOneLayersKeys(float keys[S3D_STEREO_TAP_CAPACITY]) {
  float nearestKey = S3D_INFINITY;
  bool outOfRange = false;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i) {
    bool inRange = isDeviceDepthKeyInRange(h.depth, keys[i]);
    outOfRange = outOfRange || !inRange;
    nearestKey = inRange ? min(nearestKey, keys[i]) : nearestKey;
  }
  float minDepth = outOfRange ? c.zeroParallaxDistance : S3D_INFINITY;
  if (nearestKey == S3D_INFINITY) return minDepth;  // no tap in range, or the sky at +inf
  float deviceDepth = deviceDepthKey(h.depth, nearestKey);  // the key's negation is its own inverse
  return min(minDepth, sanitizedDepth(stereoDepthFromDevice(h.depth, deviceDepth), c.zeroParallaxDistance));
}

// Listing 4.5 on a depth buffer with a first-person range. Taps whose keys all lie above the first-person layer's
// (the world, the sky, NaN) are one layer: one conversion. Otherwise every tap is converted, since the weapon's
// push may interleave the layers' depths (and a key below the range's near end is the zero-parallax plane).
float minDepthOverTwoLayersKeys(float keys[S3D_STEREO_TAP_CAPACITY]) {
  bool firstPersonTap = false;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i)
    firstPersonTap = firstPersonTap || keys[i] <= firstPersonKeyMax(h.depth);
  if (!firstPersonTap) return minDepthOverOneLayersKeys(keys);
  float minDepth = S3D_INFINITY;
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i) {
    float depth =
        sanitizedDepth(stereoDepthFromDevice(h.depth, deviceDepthKey(h.depth, keys[i])), c.zeroParallaxDistance);
    minDepth = i < c.tapCount ? min(minDepth, depth) : minDepth;
  }
  return minDepth;
}
#endif

#define S3D_GATHER_TAP_COUNT c.tapCount
#define S3D_GATHER_TAP_OFFSET_PX c.tapOffsetPx
#include "stereo_gather_source.glsl"

// The taps' nearest depth on one side of the pixel: from a host's depth buffer through its keys, else per tap.
float nearestTapDepth(int x, int y, int direction) {
#ifdef S3D_STEREO_HOST_INPUTS
  if (kHostDepthPath != S3D_HOST_GATHER_DEPTH_LINEAR) {
    float keys[S3D_STEREO_TAP_CAPACITY];
    tapKeys(x, y, direction, keys);
    return kHostDepthPath == S3D_HOST_GATHER_DEPTH_ONE_LAYER ? minDepthOverOneLayersKeys(keys)
                                                             : minDepthOverTwoLayersKeys(keys);
  }
#endif
  return minDepthOverTaps(x, y, direction);
}

// An 8-bit eye's value as its byte, rounded half away from zero as the C++ reference rounds, for the packings that
// mix or filter the eyes in the gather. (A stored eye's byte is the store's conversion, which Vulkan lets round
// ties either way; rounding every stored eye here too slowed the two-eye output: docs/RESULTS.md.)
vec4 eyeByteValue(vec4 color) { return floor(clamp(color, 0.0, 1.0) * 255.0 + 0.5) * (1.0 / 255.0); }

// Both eyes' pixel: stored in the two eyes, or (from host images) packed straight into the target at binding 2.
void writeEyes(ivec2 pixel, vec4 left, vec4 right) {
#ifdef S3D_STEREO_HOST_INPUTS
  if (kGatherOutput == S3D_HOST_GATHER_ANAGLYPH) {  // 8-bit eyes: mixed from their bytes, as the packing pass
    vec3 l = eyeByteValue(left).rgb, r = eyeByteValue(right).rgb;
    l = vec3(hostSrgbToLinear(l.r), hostSrgbToLinear(l.g), hostSrgbToLinear(l.b));
    r = vec3(hostSrgbToLinear(r.r), hostSrgbToLinear(r.g), hostSrgbToLinear(r.b));
    vec3 mixed = clamp(hostDuboisAnaglyph(l, r), 0.0, 1.0);
    imageStore(leftEye, pixel, vec4(hostLinearToSrgb(mixed.r), hostLinearToSrgb(mixed.g), hostLinearToSrgb(mixed.b), 1.0));
    return;
  }
  if (kGatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL || kGatherOutput == S3D_HOST_GATHER_TOP_BOTTOM_FULL) {
    imageStore(leftEye, pixel, left);
    imageStore(leftEye, pixel + (kGatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL ? ivec2(c.width, 0) : ivec2(0, c.height)),
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

#ifdef S3D_STEREO_HOST_HALF_PACKING
// Eye pixel `pixel` of the eye looking along `side` (+1 left, -1 right), as the reference's 8-bit eye holds it.
// Gathered before the crop test, with no branch, so a packed pixel's two eye pixels read together (returning
// early for the cropped edges was slower: docs/RESULTS.md "Every packed output from the gather").
vec4 storedEyePixel(ivec2 pixel, int side) {
  float source = gatherSourceColumn(pixel.x, side, nearestTapDepth(pixel.x, pixel.y, side));
  vec4 gathered = eyeByteValue(sampleRow(pixel.y, source));
  return pixel.x < c.cropBegin || pixel.x >= c.cropEnd ? vec4(0, 0, 0, 1) : gathered;  // cropped edges
}

vec3 linearOfStored(vec4 v) { return vec3(hostSrgbToLinear(v.r), hostSrgbToLinear(v.g), hostSrgbToLinear(v.b)); }

// Slot k of one eye squeezed from `length` pixels to `slots` along one axis: host_pack.glsl's area-weighted box
// filter in linear light over the eye pixels it covers, each gathered here instead of read from a stored eye.
vec4 squeezedEyePixel(int side, ivec2 fixedPixel, bool horizontal, int k, int length, int slots) {
  ivec2 step = horizontal ? ivec2(1, 0) : ivec2(0, 1);
  ivec2 row = horizontal ? ivec2(0, fixedPixel.y) : ivec2(fixedPixel.x, 0);
  if (length == 2 * slots) {  // an even size: two whole pixels of weight 1/2 (the loop's terms, unrolled)
    vec4 a = storedEyePixel(row + 2 * k * step, side), b = storedEyePixel(row + (2 * k + 1) * step, side);
    vec3 color = 0.5 * linearOfStored(a) + 0.5 * linearOfStored(b);
    return vec4(hostLinearToSrgb(color.r), hostLinearToSrgb(color.g), hostLinearToSrgb(color.b), 0.5 * a.a + 0.5 * b.a);
  }
  vec3 color = vec3(0);
  float alpha = 0.0;
  int begin = k * length, end = (k + 1) * length;
  for (int s = begin / slots; s * slots < end; ++s) {
    float weight = float(min(end, (s + 1) * slots) - max(begin, s * slots)) / float(length);
    vec4 v = storedEyePixel(row + s * step, side);
    color += weight * linearOfStored(v);
    alpha += weight * v.a;
  }
  return vec4(hostLinearToSrgb(color.r), hostLinearToSrgb(color.g), hostLinearToSrgb(color.b), alpha);
}

// Pixel `pixel` of a half packing: the left (top) eye's squeezed columns (rows), then the right (bottom) eye's; an
// odd size gives the spare one to the left (top) eye, as output_formats.cpp.
vec4 halfPackedPixel(ivec2 pixel) {
  bool horizontal = kGatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_HALF;
  int length = horizontal ? c.width : c.height, at = horizontal ? pixel.x : pixel.y;
  int firstSlots = (length + 1) / 2;
  bool first = at < firstSlots;
  return squeezedEyePixel(first ? 1 : -1, pixel, horizontal, first ? at : at - firstSlots, length,
                          first ? firstSlots : length - firstSlots);
}
#endif

#ifdef S3D_STEREO_BASE_DEPTH_OUTPUT
// The center device depth at the texel nearest source column u, as the hybrid's base depth pass reads it.
float deviceDepthAtSource(float u, int y) { return texelFetch(deviceDepth, ivec2(nearestSourceTexel(u), y), 0).r; }

// Both eyes' pixel and base depth (every pixel's depth: the cropped edges' too, as the base depth pass).
void gatherWithBaseDepth(ivec2 pixel) {
  float leftSource = gatherSourceColumn(pixel.x, +1, nearestTapDepth(pixel.x, pixel.y, +1));
  float rightSource = gatherSourceColumn(pixel.x, -1, nearestTapDepth(pixel.x, pixel.y, -1));
  imageStore(leftBaseDepth, pixel, vec4(deviceDepthAtSource(leftSource, pixel.y)));
  imageStore(rightBaseDepth, pixel, vec4(deviceDepthAtSource(rightSource, pixel.y)));
  bool cropped = pixel.x < c.cropBegin || pixel.x >= c.cropEnd;
  writeEyes(pixel, cropped ? vec4(0, 0, 0, 1) : sampleRow(pixel.y, leftSource),
            cropped ? vec4(0, 0, 0, 1) : sampleRow(pixel.y, rightSource));
}
#endif

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
#if defined(S3D_STEREO_BASE_DEPTH_OUTPUT)
  gatherWithBaseDepth(pixel);
#elif defined(S3D_STEREO_HOST_HALF_PACKING)
  imageStore(leftEye, pixel, halfPackedPixel(pixel));
#else
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges
    writeEyes(pixel, vec4(0, 0, 0, 1), vec4(0, 0, 0, 1));
    return;
  }
  writeEyes(pixel, sampleRow(pixel.y, gatherSourceColumn(pixel.x, +1, nearestTapDepth(pixel.x, pixel.y, +1))),
            sampleRow(pixel.y, gatherSourceColumn(pixel.x, -1, nearestTapDepth(pixel.x, pixel.y, -1))));
#endif
}
