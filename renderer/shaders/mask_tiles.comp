#version 450
// Masked render, first pass: the tiles holding a shade-mask pixel (the lighting and resolve list) and those
// tiles with their 8 neighbours (the half-resolution ambient occlusion's list: its blur and upsample reach
// up to 3 half-resolution texels, under one tile, past a masked pixel), with the indirect dispatch counts.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_COMPUTE_GROUP_SIZE, local_size_y = S3D_COMPUTE_GROUP_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
#define S3D_TILES_BINDING 1
#define S3D_SHADE_MASK_BINDING 2
#include "tiles.glsl"

shared uint anyMasked;

void main() {
  if (gl_LocalInvocationIndex == 0u) anyMasked = 0u;
  barrier();
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  ivec2 screen = ivec2(frame.screen.xy);
  bool found = false;
  for (int k = 0; k < 4; ++k) {
    ivec2 pixel = tile * S3D_TILE_SIZE + ivec2(gl_LocalInvocationID.xy) + S3D_COMPUTE_GROUP_SIZE * ivec2(k & 1, k >> 1);
    if (all(lessThan(pixel, screen)) && shadeMasked(pixel)) found = true;
  }
  if (found) atomicOr(anyMasked, 1u);
  barrier();
  if (anyMasked == 0u) return;
  // The tile and its 8 neighbours by 9 invocations at once, not as one invocation's chain of dependent global
  // atomics (measured faster on a GPU: docs/RESULTS.md).
  uint local = gl_LocalInvocationIndex;
  if (local == 0u) tileEntries[tileCount() + atomicAdd(tileHeader.lightingDispatch.x, 1u)] = packTile(tile);
  if (local >= 9u) return;
  ivec2 neighbour = tile + ivec2(int(local % 3u) - 1, int(local / 3u) - 1);
  if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, ivec2(frame.tiles.xy)))) return;
  // The first tile to flag a neighbour lists it, so each is listed once.
  if (atomicOr(tileEntries[uint(neighbour.y) * frame.tiles.x + uint(neighbour.x)], 1u) == 0u)
    tileEntries[2u * tileCount() + atomicAdd(tileHeader.ambientDispatch.x, 1u)] = packTile(neighbour);
}
