// Tiles and the shade mask, for the passes that can run on part of the image (include after renderer_shared.h
// and the `frame` uniform block, with S3D_TILES_BINDING defined, and S3D_SHADE_MASK_BINDING where the pass
// reads the mask). An unmasked render dispatches the whole tile grid; a masked one dispatches the lists that
// mask_tiles.comp built, indirectly. Masking and counting are specialization constants (0 and 1): a CPU
// rasterizer runs both sides of every branch, so a uniform flag would charge every render the masked path.
layout(constant_id = 0) const bool kMaskedRender = false;
layout(constant_id = 1) const bool kCountShaded = false;
layout(std430, binding = S3D_TILES_BINDING) buffer Tiles {
  TileHeader tileHeader;
  uint tileEntries[];  // ambient-region flags, masked tiles, ambient-region tiles, the lighting classes'
                       // tiles (tileCount() each), the tiles' light lists (S3D_LIGHT_LIST_WORDS each)
};

bool maskedRender() { return kMaskedRender; }
uint tileCount() { return frame.tiles.x * frame.tiles.y; }
uint packTile(ivec2 tile) { return uint(tile.x) | (uint(tile.y) << 16); }

// The tile this workgroup covers: its grid position, or in a masked render its list entry.
ivec2 workgroupTile(uint listStart) {
  if (!maskedRender()) return ivec2(gl_WorkGroupID.xy);
  uint packed = tileEntries[listStart + gl_WorkGroupID.x];
  return ivec2(packed & 0xffffu, packed >> 16);
}
ivec2 maskedTile() { return workgroupTile(tileCount()); }
ivec2 ambientTile() { return workgroupTile(2u * tileCount()); }

// Lighting classes (S3D_TILE_*): the tiles of a class, dispatched indirectly in masked and unmasked renders.
uint tileClassList(uint tileClass) { return (3u + tileClass) * tileCount(); }
ivec2 classTile(uint tileClass) {
  uint packed = tileEntries[tileClassList(tileClass) + gl_WorkGroupID.x];
  return ivec2(packed & 0xffffu, packed >> 16);
}
// The first word of a tile's light list: its counts, then its lights' indices in the frame's light buffer.
uint tileLightList(ivec2 tile) {
  return (3u + S3D_TILE_CLASSES) * tileCount() + (uint(tile.y) * frame.tiles.x + uint(tile.x)) * S3D_LIGHT_LIST_WORDS;
}
// The light buffer index of a list's n-th light.
uint listedLight(uint list, uint n) { return (tileEntries[list + 1u + (n >> 2)] >> ((n & 3u) * 8u)) & 0xffu; }

// Adds to a pass's shaded-pixel counter when the renderer counts (tests).
void countShaded(uint slot, uint pixels) {
  if (kCountShaded && pixels > 0u) atomicAdd(tileHeader.shadedPixels[slot], pixels);
}

#ifdef S3D_SHADE_MASK_BINDING
layout(binding = S3D_SHADE_MASK_BINDING, r32ui) uniform readonly uimage2D shadeMask;  // output size

// Whether a render pixel is shaded: always without a mask; with one, where its output pixel's value reaches the
// threshold (every sample of a supersampled output pixel alike).
bool shadeMasked(ivec2 renderPixel) {
  if (!maskedRender()) return true;
  return imageLoad(shadeMask, renderPixel / int(frame.options.x)).r >= frame.tiles.z;
}
#endif
