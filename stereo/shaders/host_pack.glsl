// The host pass's output packing: both eyes into one target (side-by-side, top-bottom, Dubois anaglyph) with
// output_formats.cpp's math: half packing box-filters pixel pairs in linear light, full packing copies, the
// anaglyph mixes linear light. Included with S3D_HOST_COLOR_FORMAT set (the eyes' and the target's format).
#include "s3d/stereo/host_pass_shared.h"

layout(local_size_x = S3D_HOST_GROUP_SIZE, local_size_y = S3D_HOST_GROUP_SIZE) in;
layout(binding = 0, S3D_HOST_COLOR_FORMAT) uniform readonly image2D leftEye;
layout(binding = 1, S3D_HOST_COLOR_FORMAT) uniform readonly image2D rightEye;
layout(binding = 2, S3D_HOST_COLOR_FORMAT) uniform writeonly image2D target;
layout(push_constant) uniform Push { HostPackConstants c; };

vec3 toLinear(vec3 v) {
  return c.eyesEncoded != 0 ? vec3(hostSrgbToLinear(v.r), hostSrgbToLinear(v.g), hostSrgbToLinear(v.b)) : v;
}
vec3 fromLinear(vec3 v) {
  return c.eyesEncoded != 0 ? vec3(hostLinearToSrgb(v.r), hostLinearToSrgb(v.g), hostLinearToSrgb(v.b)) : v;
}

vec4 eyeAt(bool left, ivec2 p) { return left ? imageLoad(leftEye, p) : imageLoad(rightEye, p); }

// Area-weighted box filter of one eye squeezed from `length` samples to `slots` along one axis (slots <= length):
// slot k covers [k*length, (k+1)*length) and source s covers [s*slots, (s+1)*slots).
vec4 squeezed(bool left, ivec2 fixedPixel, bool horizontal, int k, int length, int slots) {
  vec3 color = vec3(0);
  float alpha = 0.0;
  int begin = k * length, end = (k + 1) * length;
  for (int s = begin / slots; s * slots < end; ++s) {
    float weight = float(min(end, (s + 1) * slots) - max(begin, s * slots)) / float(length);
    vec4 v = eyeAt(left, horizontal ? ivec2(s, fixedPixel.y) : ivec2(fixedPixel.x, s));
    color += weight * toLinear(v.rgb);
    alpha += weight * v.a;
  }
  return vec4(fromLinear(color), alpha);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  int w = c.eyeWidth, h = c.eyeHeight;
  vec4 result;
  if (c.mode == S3D_HOST_PACK_ANAGLYPH) {
    if (pixel.x >= w || pixel.y >= h) return;
    vec3 l = toLinear(imageLoad(leftEye, pixel).rgb), r = toLinear(imageLoad(rightEye, pixel).rgb);
    vec3 mixed = hostDuboisAnaglyph(l, r);
    if (c.eyesEncoded != 0) mixed = clamp(mixed, 0.0, 1.0);
    result = vec4(fromLinear(mixed), 1.0);
  } else if (c.mode == S3D_HOST_PACK_SIDE_BY_SIDE_FULL) {
    if (pixel.x >= 2 * w || pixel.y >= h) return;
    result = pixel.x < w ? imageLoad(leftEye, pixel) : imageLoad(rightEye, pixel - ivec2(w, 0));
  } else if (c.mode == S3D_HOST_PACK_TOP_BOTTOM_FULL) {
    if (pixel.x >= w || pixel.y >= 2 * h) return;
    result = pixel.y < h ? imageLoad(leftEye, pixel) : imageLoad(rightEye, pixel - ivec2(0, h));
  } else if (c.mode == S3D_HOST_PACK_SIDE_BY_SIDE_HALF) {
    if (pixel.x >= w || pixel.y >= h) return;
    int leftColumns = (w + 1) / 2;  // odd width: the left eye takes the spare column
    bool left = pixel.x < leftColumns;
    result = left ? squeezed(true, pixel, true, pixel.x, w, leftColumns)
                  : squeezed(false, pixel, true, pixel.x - leftColumns, w, w - leftColumns);
  } else {
    if (pixel.x >= w || pixel.y >= h) return;
    int topRows = (h + 1) / 2;
    bool top = pixel.y < topRows;
    result = top ? squeezed(true, pixel, false, pixel.y, h, topRows)
                 : squeezed(false, pixel, false, pixel.y - topRows, h, h - topRows);
  }
  imageStore(target, pixel, result);
}
