// Row tiles (row_tile_shared.h): the workgroup's run of one row plus a margin each side, in shared memory.
// Included by the tiled passes after they declare centerColor and linearDepth. The host runs them only where
// the margin fits (usesRowTiles), so every depth fetch is loaded; a color fetch beyond it reads the image.
#include "s3d/stereo/row_tile_shared.h"
#include "s3d/stereo/stereo_shared.h"

layout(local_size_x = S3D_STEREO_ROW_TILE, local_size_y = 1) in;

shared float tileDepth[S3D_STEREO_ROW_TILE_SPAN];  // sanitized linear depth
shared uint tileColor[S3D_STEREO_ROW_TILE_SPAN];   // RGBA8 packed: 4 bytes a texel, as in the image
shared uint tileDepthVaries;                       // != 0: two neighbouring loaded depths differ

int tileBegin = 0;  // first loaded column
int tileEnd = 0;    // one past the last loaded column

// Loads the columns [interiorBegin - margin, interiorEnd + margin) of row y (clamped to the image), one texel
// per invocation per step so neighbouring invocations read neighbouring texels. Returns whether every loaded
// depth is the same (the tile's min equals its max). Every invocation of the group must call it (barriers).
bool loadRowTile(int interiorBegin, int interiorEnd, int y, int margin, int width, float zeroParallaxDistance) {
  margin = min(margin, S3D_STEREO_ROW_TILE_MARGIN);
  tileBegin = max(interiorBegin - margin, 0);
  tileEnd = min(interiorEnd + margin, width);
  int count = tileEnd - tileBegin;
  int local = int(gl_LocalInvocationIndex);
  if (local == 0) tileDepthVaries = 0u;
  for (int i = local; i < count; i += S3D_STEREO_ROW_TILE) {
    ivec2 texel = ivec2(tileBegin + i, y);
    tileDepth[i] = sanitizedDepth(imageLoad(linearDepth, texel).r, zeroParallaxDistance);
    tileColor[i] = packUnorm4x8(imageLoad(centerColor, texel));
  }
  barrier();
  // Flat iff no neighbouring pair differs; every writer stores the same value, so no atomic is needed.
  bool varies = false;
  for (int i = local; i + 1 < count; i += S3D_STEREO_ROW_TILE) varies = varies || tileDepth[i] != tileDepth[i + 1];
  if (varies) tileDepthVaries = 1u;
  barrier();
  return tileDepthVaries == 0u;
}

// Sanitized depth at column x (already clamped to the image, and within the margin of a tile pixel; the index
// clamp only keeps a broken caller inside the array).
float tileDepthAt(int x) {
  return tileDepth[clamp(x - tileBegin, 0, S3D_STEREO_ROW_TILE_SPAN - 1)];
}

// Color at column x (already clamped to the image).
vec4 tileColorAt(int x, int y) {
  int i = x - tileBegin;
  if (i >= 0 && x < tileEnd) return unpackUnorm4x8(tileColor[i]);
  return imageLoad(centerColor, ivec2(x, y));
}

// The per-pixel passes' sampleRow on the tile: horizontal linear filter at texel coordinate u, clamped to the edge.
vec4 tileSampleRow(int y, float u, int width) {
  float base = floor(u);
  float fraction = u - base;
  vec4 a = tileColorAt(clamp(int(base), 0, width - 1), y);
  vec4 b = tileColorAt(clamp(int(base) + 1, 0, width - 1), y);
  return a * (1.0 - fraction) + b * fraction;
}
