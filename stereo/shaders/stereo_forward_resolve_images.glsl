// What both key-image resolves share: depth and keys read from the images, and the other pair of z-buffers,
// which the resolve empties for the next record (ForwardStereoPass alternates two pairs), so no frame after the
// first needs a clear dispatch.
layout(binding = 6, r32ui) uniform writeonly uimage2D nextLeftKeys;
layout(binding = 7, r32ui) uniform writeonly uimage2D nextRightKeys;

float depthAt(int x, int y) { return imageLoad(linearDepth, ivec2(x, y)).r; }

uint keyAt(bool leftEyeKeys, int x, int y) {
  return leftEyeKeys ? imageLoad(leftKeys, ivec2(x, y)).r : imageLoad(rightKeys, ivec2(x, y)).r;
}

void emptyNextKeys(ivec2 pixel) {
  imageStore(nextLeftKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
  imageStore(nextRightKeys, pixel, uvec4(S3D_FORWARD_EMPTY));
}
