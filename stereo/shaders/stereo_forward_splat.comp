#version 450
// Forward method, dispatch 2 of 3: each center pixel writes its key into every eye pixel it covers, nearest wins.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"

void splatKeys(bool leftEyeKeys, int y, float from, float to, float depth, int source) {
  int end = min(forwardFirstColumn(to), c.width);
  for (int column = max(forwardFirstColumn(from), 0); column < end; ++column) {
    uint key = forwardKey(depth, source, column);
    if (leftEyeKeys) imageAtomicMin(leftKeys, ivec2(column, y), key);
    else imageAtomicMin(rightKeys, ivec2(column, y), key);
  }
}

void splatEye(ivec2 pixel, float direction) {
  float here, previous, next;
  if (!place(pixel.x, pixel.y, direction, here)) return;
  float depth = depthAt(pixel.x, pixel.y);
  bool leftEyeKeys = direction > 0.0;
  bool previousKnown = place(pixel.x - 1, pixel.y, direction, previous);
  bool nextKnown = place(pixel.x + 1, pixel.y, direction, next);
  if (!(previousKnown && forwardConnected(previous, here)))
    splatKeys(leftEyeKeys, pixel.y, here - 0.5, here, depth, pixel.x);  // open left end: half a pixel
  if (nextKnown && forwardConnected(here, next))
    splatKeys(leftEyeKeys, pixel.y, here, next, min(depth, depthAt(pixel.x + 1, pixel.y)), pixel.x);
  else
    splatKeys(leftEyeKeys, pixel.y, here, here + 0.5, depth, pixel.x);  // open right end
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  splatEye(pixel, 1.0);
  splatEye(pixel, -1.0);
}
