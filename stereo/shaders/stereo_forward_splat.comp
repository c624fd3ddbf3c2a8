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

// The pixel and its row neighbours' depths (unknown outside the row) are read once for both eyes.
void splatEye(ivec2 pixel, float direction, float previousDepth, float depth, float nextDepth) {
  bool leftEyeKeys = direction > 0.0;
  float here = forwardPosition(c, pixel.x, direction, depth);
  bool previousKnown = forwardKnownDepth(previousDepth);
  bool nextKnown = forwardKnownDepth(nextDepth);
  float previous = previousKnown ? forwardPosition(c, pixel.x - 1, direction, previousDepth) : 0.0;
  float next = nextKnown ? forwardPosition(c, pixel.x + 1, direction, nextDepth) : 0.0;
  if (!(previousKnown && forwardConnected(previous, here)))
    splatKeys(leftEyeKeys, pixel.y, here - 0.5, here, depth, pixel.x);  // open left end: half a pixel
  if (nextKnown && forwardConnected(here, next))
    splatKeys(leftEyeKeys, pixel.y, here, next, min(depth, nextDepth), pixel.x);
  else
    splatKeys(leftEyeKeys, pixel.y, here, here + 0.5, depth, pixel.x);  // open right end
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  float depth = depthAt(pixel.x, pixel.y);
  if (!forwardKnownDepth(depth)) return;  // unknown: never placed
  float previousDepth = pixel.x > 0 ? depthAt(pixel.x - 1, pixel.y) : -1.0;
  float nextDepth = pixel.x + 1 < c.width ? depthAt(pixel.x + 1, pixel.y) : -1.0;
  splatEye(pixel, 1.0, previousDepth, depth, nextDepth);
  splatEye(pixel, -1.0, previousDepth, depth, nextDepth);
}
