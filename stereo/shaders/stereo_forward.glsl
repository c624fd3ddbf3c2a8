// What every forward-method shader shares (forward_shared.h): the four eye-pair bindings, the constants, and
// placement and filtering on top of depthAt, which each shader defines (image or shared memory). The C++ twin
// is forward_reference.cpp.
#include "s3d/stereo/forward_shared.h"

layout(binding = 0, rgba8) uniform readonly image2D centerColor;
layout(binding = 1, r32f) uniform readonly image2D linearDepth;
layout(binding = 2, rgba8) uniform writeonly image2D leftEye;
layout(binding = 3, rgba8) uniform writeonly image2D rightEye;

layout(push_constant) uniform Push { ForwardConstants c; };

// The linear depth of center pixel (x, y), x inside the row.
float depthAt(int x, int y);

// A pixel's eye position; known is false outside the row or for unknown depth.
bool place(int x, int y, float direction, out float position) {
  position = 0.0;
  if (x < 0 || x >= c.width) return false;
  float d = depthAt(x, y);
  if (!forwardKnownDepth(d)) return false;
  position = forwardPosition(c, x, direction, d);
  return true;
}

// Horizontal linear filter at texel coordinate u, clamped to the edge: the seed's sampleRow.
vec4 sampleRow(int y, float u) {
  float base = floor(u);
  float fraction = u - base;
  vec4 a = imageLoad(centerColor, ivec2(clamp(int(base), 0, c.width - 1), y));
  vec4 b = imageLoad(centerColor, ivec2(clamp(int(base) + 1, 0, c.width - 1), y));
  return a * (1.0 - fraction) + b * fraction;
}
