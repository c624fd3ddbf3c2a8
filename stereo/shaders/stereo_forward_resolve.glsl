// The forward method's resolve (forward_shared.h) on top of keyAt, which each shader defines: a z-buffer read
// from an image or from shared memory, after the whole row was splatted.

// The winning key of eye pixel (x, y), x inside the row, or S3D_FORWARD_EMPTY.
uint keyAt(bool leftEyeKeys, int x, int y);

// The mean of the pixels from `first` in steps of `step` (up to S3D_FORWARD_FILL_TAPS, before `stop`) on the
// surface of parallax `parallax` (within 1 px); count 0 when `first` is not on it. All taps are read before the
// first is judged (clamped to the row), so their loads are in flight together; the sum is in the same order.
vec4 surfaceMean(int y, int first, int step, int stop, float parallax, out int count) {
  float depths[S3D_FORWARD_FILL_TAPS];
  vec4 colors[S3D_FORWARD_FILL_TAPS];
  for (int k = 0; k < S3D_FORWARD_FILL_TAPS; ++k) {
    int x = clamp(first + k * step, 0, c.width - 1);
    depths[k] = depthAt(x, y);
    colors[k] = imageLoad(centerColor, ivec2(x, y));
  }
  vec4 sum = vec4(0.0);
  count = 0;
  for (int k = 0; k < S3D_FORWARD_FILL_TAPS; ++k) {
    int x = first + k * step;
    if (x < 0 || x >= c.width || x == stop) break;
    float d = depths[k];
    if (!forwardKnownDepth(d) || abs(forwardParallaxPx(c, d) - parallax) > 1.0) break;
    sum += colors[k];
    ++count;
  }
  return count > 0 ? sum / float(count) : sum;
}

// The nearest covered eye pixel from `column` in steps of `step` (+-1), at most c.fillSearchPx away, or -1. The
// keys are read S3D_FORWARD_SCAN_CHUNK at a time: independent loads in flight together instead of one memory
// round trip per pixel of the hole (the hole pixels' latency bounds the resolve on a GPU).
int nearestCovered(bool leftEyeKeys, int column, int y, int step) {
  for (int i = 1; i <= c.fillSearchPx; i += S3D_FORWARD_SCAN_CHUNK) {
    uint keys[S3D_FORWARD_SCAN_CHUNK];
    for (int j = 0; j < S3D_FORWARD_SCAN_CHUNK; ++j)
      keys[j] = keyAt(leftEyeKeys, clamp(column + step * (i + j), 0, c.width - 1), y);
    for (int j = 0; j < S3D_FORWARD_SCAN_CHUNK; ++j) {
      int x = column + step * (i + j);
      if (i + j > c.fillSearchPx || x < 0 || x >= c.width) return -1;
      if (keys[j] != S3D_FORWARD_EMPTY) return x;
    }
  }
  return -1;
}

// A hole pixel (forward_shared.h): the background between the hole's two edges in the center row, else the
// surface behind the farther edge.
vec4 fillHole(bool leftEyeKeys, int column, int y) {
  int left = nearestCovered(leftEyeKeys, column, y, -1);
  int right = nearestCovered(leftEyeKeys, column, y, 1);
  if (left < 0 && right < 0) return imageLoad(centerColor, ivec2(column, y));
  int count;
  if (left >= 0 && right >= 0) {
    // Center pixels between the edges' sources behind both edges were hidden in this eye (a gap between occluders).
    int leftSource = forwardKeySource(keyAt(leftEyeKeys, left, y), left);
    int rightSource = forwardKeySource(keyAt(leftEyeKeys, right, y), right);
    int low = min(leftSource, rightSource), high = max(leftSource, rightSource);
    float farthest = max(forwardParallaxPx(c, depthAt(leftSource, y)), forwardParallaxPx(c, depthAt(rightSource, y))) + 1.0;
    int background = -1;
    int end = min(high, low + c.fillSearchPx + 1);  // the scanned columns: low + 1 .. end - 1
    for (int first = low + 1; first < end; first += S3D_FORWARD_SCAN_CHUNK) {
      float depths[S3D_FORWARD_SCAN_CHUNK];  // read together, judged in order (as the C++ twin)
      for (int j = 0; j < S3D_FORWARD_SCAN_CHUNK; ++j) depths[j] = depthAt(min(first + j, end - 1), y);
      for (int j = 0; j < S3D_FORWARD_SCAN_CHUNK && first + j < end; ++j) {
        float d = depths[j];
        if (forwardKnownDepth(d) && forwardParallaxPx(c, d) > farthest) {
          farthest = forwardParallaxPx(c, d);
          background = first + j;
        }
      }
    }
    if (background >= 0) return surfaceMean(y, background, 1, high, farthest, count);
  }
  bool useRight = left < 0 || (right >= 0 && forwardKeyDepth(keyAt(leftEyeKeys, right, y)) >
                                                 forwardKeyDepth(keyAt(leftEyeKeys, left, y)));
  int edge = useRight ? right : left;
  int source = forwardKeySource(keyAt(leftEyeKeys, edge, y), edge);
  int away = useRight ? 1 : -1;
  vec4 mean = surfaceMean(y, source + away * S3D_FORWARD_FILL_SKIP, away, -1, forwardParallaxPx(c, depthAt(source, y)), count);
  return count > 0 ? mean : imageLoad(centerColor, ivec2(source, y));
}

// A covered eye pixel (key not S3D_FORWARD_EMPTY): its winning source at the sub-pixel position.
vec4 resolveCovered(ivec2 pixel, float direction, uint key) {
  int source = forwardKeySource(key, pixel.x);
  float position, nextPosition;
  place(source, pixel.y, direction, position);
  bool connected = place(source + 1, pixel.y, direction, nextPosition) && forwardConnected(position, nextPosition);
  return sampleRow(pixel.y, forwardSourcePosition(pixel.x, source, position, connected, nextPosition));
}

// Eye pixel `pixel` (inside the image) of both eyes. The hole fill is one code path whose eye is data: a
// subgroup with left-eye holes in some lanes and right-eye holes in others waits for one chain of dependent
// hole reads, not for the left eye's and then the right eye's (the fill's cost is that latency, docs/RESULTS.md).
void resolvePixel(ivec2 pixel) {
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges, as in the seed
    imageStore(leftEye, pixel, vec4(0, 0, 0, 1));
    imageStore(rightEye, pixel, vec4(0, 0, 0, 1));
    return;
  }
  uint leftKey = keyAt(true, pixel.x, pixel.y);
  uint rightKey = keyAt(false, pixel.x, pixel.y);
  bool leftHole = leftKey == S3D_FORWARD_EMPTY, rightHole = rightKey == S3D_FORWARD_EMPTY;
  if (!leftHole) imageStore(leftEye, pixel, resolveCovered(pixel, 1.0, leftKey));
  if (!rightHole) imageStore(rightEye, pixel, resolveCovered(pixel, -1.0, rightKey));
  if (!leftHole && !rightHole) return;
  vec4 fill = fillHole(leftHole, pixel.x, pixel.y);  // the left eye's hole if it has one, else the right's
  if (leftHole) imageStore(leftEye, pixel, fill);
  else imageStore(rightEye, pixel, fill);
  if (leftHole && rightHole) imageStore(rightEye, pixel, fillHole(false, pixel.x, pixel.y));
}
