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
  if (gl_LocalInvocationIndex != 0u || anyMasked == 0u) return;
  uint slot = atomicAdd(tileHeader.lightingDispatch.x, 1u);
  tileEntries[tileCount() + slot] = packTile(tile);
  ivec2 grid = ivec2(frame.tiles.xy);
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) {
      ivec2 neighbour = tile + ivec2(x, y);
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, grid))) continue;
      // The first tile to flag a neighbour lists it, so each is listed once.
      if (atomicOr(tileEntries[uint(neighbour.y) * frame.tiles.x + uint(neighbour.x)], 1u) == 0u)
        tileEntries[2u * tileCount() + atomicAdd(tileHeader.ambientDispatch.x, 1u)] = packTile(neighbour);
    }
}
