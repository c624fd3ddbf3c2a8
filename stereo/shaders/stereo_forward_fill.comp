#version 450
// Forward method, key-image kernel, hole fill: one invocation per eye, row and segment of
// S3D_FORWARD_FILL_SEGMENT columns finds the segment's hole runs (empty keys) and fills each once
// (stereo_forward_resolve.glsl, fillHoleRun). It reads only what the splat wrote and writes only hole pixels,
// the pixels the resolve leaves, so it needs no barrier after the resolve. Apart from the resolve, every lane of
// a subgroup works on holes: inside the resolve one lane of 32 filled a run while the others waited.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward.glsl"
#include "stereo_forward_key_images.glsl"
#include "stereo_forward_resolve.glsl"

layout(local_size_x = S3D_FORWARD_GROUP_SIZE, local_size_y = S3D_FORWARD_GROUP_SIZE) in;

float depthAt(int x, int y) { return imageLoad(linearDepth, ivec2(x, y)).r; }

uint keyAt(bool leftEyeKeys, int x, int y) {
  return leftEyeKeys ? imageLoad(leftKeys, ivec2(x, y)).r : imageLoad(rightKeys, ivec2(x, y)).r;
}

void main() {
  int y = int(gl_GlobalInvocationID.y);
  int segment = int(gl_GlobalInvocationID.x);
  bool leftEyeKeys = gl_GlobalInvocationID.z == 0u;
  int begin = max(segment * S3D_FORWARD_FILL_SEGMENT, c.cropBegin);
  int end = min((segment + 1) * S3D_FORWARD_FILL_SEGMENT, min(c.cropEnd, c.width));
  if (y >= c.height || begin >= end) return;
  uint holes = 0u;  // bit i: column begin + i has no surface; all keys read together
  for (int i = 0; i < S3D_FORWARD_FILL_SEGMENT; ++i)
    if (keyAt(leftEyeKeys, min(begin + i, end - 1), y) == S3D_FORWARD_EMPTY && begin + i < end) holes |= 1u << i;
  uint runStarts = holes & ~(holes << 1);  // a hole whose left neighbour in the segment is covered, or the first
  while (runStarts != 0u) {
    int i = findLSB(runStarts);
    runStarts &= runStarts - 1u;
    fillHoleRun(leftEyeKeys, begin + i, y);
  }
}
