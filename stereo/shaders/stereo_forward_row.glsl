// Forward method, row kernel: one workgroup per image row runs the whole method in one dispatch. The row's
// depth and both eyes' z-buffers live in shared memory: load and empty them, splat every center pixel with a
// shared atomic minimum, barrier, resolve every eye pixel from shared memory. Same math as the key-image
// kernel (stereo_forward_splat.glsl, stereo_forward_resolve.glsl), so the same eyes bit for bit. With
// S3D_FORWARD_ROW_WRITES_KEYS it also stores the z-buffers into the key images for a following pass.
#include "stereo_forward.glsl"
#ifdef S3D_FORWARD_ROW_WRITES_KEYS
#include "stereo_forward_key_images.glsl"
#endif
#include "stereo_forward_splat.glsl"
#include "stereo_forward_resolve.glsl"

layout(local_size_x = S3D_FORWARD_ROW_GROUP_SIZE) in;
// Columns the shared arrays hold (the host sets it to the width rounded up; it is never below the width).
layout(constant_id = 0) const int rowCapacity = S3D_FORWARD_ROW_CAPACITY_STEP;

shared float rowDepth[rowCapacity];    // the center row's linear depth, as in the image
shared uint rowKeys[2 * rowCapacity];  // the left eye's z-buffer, then the right eye's

float depthAt(int x, int y) { return rowDepth[x]; }

uint keyAt(bool leftEyeKeys, int x, int y) { return rowKeys[leftEyeKeys ? x : rowCapacity + x]; }

void splatKey(bool leftEyeKeys, int column, int y, uint key) {
  atomicMin(rowKeys[leftEyeKeys ? column : rowCapacity + column], key);
}

void main() {
  int y = int(gl_WorkGroupID.y);
  int first = int(gl_LocalInvocationID.x);
  // Neighbouring invocations on neighbouring columns: coalesced loads and stores.
  for (int x = first; x < c.width; x += S3D_FORWARD_ROW_GROUP_SIZE) {
    rowDepth[x] = imageLoad(linearDepth, ivec2(x, y)).r;
    rowKeys[x] = S3D_FORWARD_EMPTY;
    rowKeys[rowCapacity + x] = S3D_FORWARD_EMPTY;
  }
  barrier();
  for (int x = first; x < c.width; x += S3D_FORWARD_ROW_GROUP_SIZE) splatPixel(ivec2(x, y));
  barrier();
  for (int x = first; x < c.width; x += S3D_FORWARD_ROW_GROUP_SIZE) {
#ifdef S3D_FORWARD_ROW_WRITES_KEYS
    imageStore(leftKeys, ivec2(x, y), uvec4(rowKeys[x]));
    imageStore(rightKeys, ivec2(x, y), uvec4(rowKeys[rowCapacity + x]));
#endif
    resolvePixel(ivec2(x, y));
  }
}
