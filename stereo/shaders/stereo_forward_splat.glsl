// The forward method's splat (forward_shared.h) on top of splatKey, which each shader defines: the z-buffer's
// atomic minimum in an image or in shared memory.

// Keeps the smaller of `key` and the eye pixel's key (nearest wins).
void splatKey(bool leftEyeKeys, int column, int y, uint key);

void splatKeys(bool leftEyeKeys, int y, float from, float to, float depth, int source) {
  float direction = leftEyeKeys ? 1.0 : -1.0;
  int end = min(forwardFirstColumn(to, direction), c.width);
  for (int column = max(forwardFirstColumn(from, direction), 0); column < end; ++column)
    splatKey(leftEyeKeys, column, y, forwardKey(depth, source, column));
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

// Center pixel `pixel` (inside the image) into both eyes' z-buffers.
void splatPixel(ivec2 pixel) {
  float depth = depthAt(pixel.x, pixel.y);
  if (!forwardKnownDepth(depth)) return;  // unknown: never placed
  float previousDepth = pixel.x > 0 ? depthAt(pixel.x - 1, pixel.y) : -1.0;
  float nextDepth = pixel.x + 1 < c.width ? depthAt(pixel.x + 1, pixel.y) : -1.0;
  splatEye(pixel, 1.0, previousDepth, depth, nextDepth);
  splatEye(pixel, -1.0, previousDepth, depth, nextDepth);
}
