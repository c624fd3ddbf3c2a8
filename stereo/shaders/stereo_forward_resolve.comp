#version 450
// Forward method, dispatch 3 of 3: each eye pixel shows its winning source at the sub-pixel position, or fills
// a disocclusion from the background side.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"

uint keyAt(bool leftEyeKeys, int x, int y) {
  return leftEyeKeys ? imageLoad(leftKeys, ivec2(x, y)).r : imageLoad(rightKeys, ivec2(x, y)).r;
}

vec4 fillHole(bool leftEyeKeys, int column, int y) {
  int left = -1, right = -1;
  for (int i = 1; i <= c.fillSearchPx && left < 0 && column - i >= 0; ++i)
    if (keyAt(leftEyeKeys, column - i, y) != S3D_FORWARD_EMPTY) left = column - i;
  for (int i = 1; i <= c.fillSearchPx && right < 0 && column + i < c.width; ++i)
    if (keyAt(leftEyeKeys, column + i, y) != S3D_FORWARD_EMPTY) right = column + i;
  if (left < 0 && right < 0) return imageLoad(centerColor, ivec2(column, y));
  bool useRight = left < 0 || (right >= 0 && forwardKeyDepth(keyAt(leftEyeKeys, right, y)) >
                                                 forwardKeyDepth(keyAt(leftEyeKeys, left, y)));
  int edge = useRight ? right : left;
  int source = forwardKeySource(keyAt(leftEyeKeys, edge, y), edge);
  int away = useRight ? 1 : -1;
  float edgeParallax = forwardParallaxPx(c, depthAt(source, y));
  vec4 sum = vec4(0.0);
  int count = 0;
  for (int k = S3D_FORWARD_FILL_SKIP; k < S3D_FORWARD_FILL_SKIP + S3D_FORWARD_FILL_TAPS; ++k) {
    int x = source + away * k;
    if (x < 0 || x >= c.width) break;
    float d = depthAt(x, y);
    if (!forwardKnownDepth(d) || abs(forwardParallaxPx(c, d) - edgeParallax) > 1.0) break;
    sum += imageLoad(centerColor, ivec2(x, y));
    ++count;
  }
  if (count == 0) return imageLoad(centerColor, ivec2(source, y));
  return sum / float(count);
}

vec4 resolveEye(ivec2 pixel, float direction) {
  bool leftEyeKeys = direction > 0.0;
  uint key = keyAt(leftEyeKeys, pixel.x, pixel.y);
  if (key == S3D_FORWARD_EMPTY) return fillHole(leftEyeKeys, pixel.x, pixel.y);
  int source = forwardKeySource(key, pixel.x);
  float position, nextPosition;
  place(source, pixel.y, direction, position);
  bool connected = place(source + 1, pixel.y, direction, nextPosition) && forwardConnected(position, nextPosition);
  return sampleRow(pixel.y, forwardSourcePosition(pixel.x, source, position, connected, nextPosition));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= c.width || pixel.y >= c.height) return;
  if (pixel.x < c.cropBegin || pixel.x >= c.cropEnd) {  // cropped edges, as in the seed
    imageStore(leftEye, pixel, vec4(0, 0, 0, 1));
    imageStore(rightEye, pixel, vec4(0, 0, 0, 1));
    return;
  }
  imageStore(leftEye, pixel, resolveEye(pixel, 1.0));
  imageStore(rightEye, pixel, resolveEye(pixel, -1.0));
}
