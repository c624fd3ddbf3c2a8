#version 450
// Lighting, first step (section 4.3.3's light culling): per tile of S3D_TILE_SIZE^2 render pixels, the
// view-depth range of its shaded surface points culls the point and spot lights (sphereTouchesTile) into the
// tile's light list (in light order: a fixed summation order); then the tile joins the list of its class: sky
// only, surfaces no light reaches, surfaces with lights none of which has a shadow map, or with some that do. The
// lighting pass shades each list with a variant compiled for it, so a tile pays for the work it needs only, on a
// CPU rasterizer too (which runs every branch and every loop body at least once). A masked render classifies the
// listed tiles by their shade-mask pixels.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

// Each thread reduces kThreadPixels pixels (row-major within the tile) in registers before one shared atomic. The
// thread count is specialized (constant 2) per device: a CPU rasterizer pays per invocation and per barrier, and
// runs shared atomics lane by lane, so it takes one SIMD vector of threads; one-dimensional, as it fills its lanes
// along x only. At most 32 pixels a thread (a bit mask of its first-person pixels).
layout(constant_id = 2) const uint kThreads = 64u;
layout(local_size_x_id = 2) in;
const uint kThreadPixels = S3D_TILE_SIZE * S3D_TILE_SIZE / kThreads;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(std430, binding = 2) readonly buffer Lights { LightConstants lights[]; };
#define S3D_TILES_BINDING 3
#define S3D_SHADE_MASK_BINDING 4
#include "tiles.glsl"
#include "surface.glsl"
layout(push_constant) uniform Push { LightingConstants lighting; };

shared uint tileNearest, tileFarthest;  // view depths as order-preserving bits
shared uint tileHasFirstPerson;
shared uint tileLightBits[S3D_LIGHT_MASK_WORDS];       // culled-in lights, one bit each
shared uint tileLightIndices[S3D_LIGHT_LIST_WORDS - 1];  // the same as a list (byte entries, as stored)

// Bits [0, n) of a 32-bit word (n clamped to 0..32).
uint bitsBelow(int n) { return n >= 32 ? 0xffffffffu : n <= 0 ? 0u : (1u << uint(n)) - 1u; }

// The render pixel of a tile's n-th pixel (row-major).
ivec2 tilePixel(ivec2 tile, uint n) { return tile * S3D_TILE_SIZE + ivec2(n % S3D_TILE_SIZE, n / S3D_TILE_SIZE); }

void main() {
  uint local = gl_LocalInvocationIndex;
  if (local == 0u) {
    tileNearest = 0xffffffffu;
    tileFarthest = 0u;
    tileHasFirstPerson = 0u;
  }
  if (local < S3D_LIGHT_MASK_WORDS) tileLightBits[local] = 0u;
  for (uint w = local; w < S3D_LIGHT_LIST_WORDS - 1u; w += kThreads) tileLightIndices[w] = 0u;
  barrier();

  // 1. The view-depth range of the tile's shaded surface points (in the world layer's view space). A world-layer
  // point's view depth is its linear depth; a first-person point's is its world position's depth in the world
  // layer's view, so only those pixels (rare: the weapon) reconstruct the position, in a loop over them.
  ivec2 tile = maskedTile();
  uint first = local * kThreadPixels;  // this thread's first pixel in the tile, row-major
  uint nearest = 0xffffffffu, farthest = 0u, firstPersonPixels = 0u;
  for (uint i = 0u; i < kThreadPixels; ++i) {
    ivec2 pixel = tilePixel(tile, first + i);
    bool shaded = all(lessThan(pixel, ivec2(frame.screen.xy))) && shadeMasked(pixel);
    float device = shaded ? texelFetch(deviceDepth, pixel, 0).r : 0.0;
    if (shaded && !isSkyDeviceDepth(frame.linearDepth, device)) {
      if (isFirstPersonDeviceDepth(frame.linearDepth, device)) {
        firstPersonPixels |= 1u << i;
      } else {
        uint bits = orderedBits(linearDepthFromDepthBuffer(frame.linearDepth, device));
        nearest = min(nearest, bits);
        farthest = max(farthest, bits);
      }
    }
  }
  for (uint pixels = firstPersonPixels; pixels != 0u; pixels &= pixels - 1u) {
    ivec2 pixel = tilePixel(tile, first + uint(findLSB(pixels)));
    Surface surface = surfaceAt(pixel, texelFetch(deviceDepth, pixel, 0).r);
    uint bits = orderedBits(dot(frame.worldViewDepth, vec4(surface.position, 1.0)));
    nearest = min(nearest, bits);
    farthest = max(farthest, bits);
  }
  if (nearest <= farthest) {
    atomicMin(tileNearest, nearest);
    atomicMax(tileFarthest, farthest);
  }
  if (firstPersonPixels != 0u) atomicOr(tileHasFirstPerson, 1u);
  barrier();

  // 2. The lights whose sphere reaches that range within the tile's rays: each thread every kThreads-th light.
  bool surfaces = tileNearest <= tileFarthest;
  if (surfaces) {
    vec2 depthRange = vec2(orderedFloat(tileNearest), orderedFloat(tileFarthest));
    vec2 lo = vec2(tile * S3D_TILE_SIZE) * frame.screen.zw * 2.0 - 1.0;
    vec2 hi = vec2(min((tile + 1) * S3D_TILE_SIZE, ivec2(frame.screen.xy))) * frame.screen.zw * 2.0 - 1.0;
    for (uint index = local; index < lighting.lightCount; index += kThreads) {
      LightConstants light = lights[index];
      if (sphereTouchesTile(light.viewPosition.xyz, light.positionRadius.w, depthRange, vec4(lo, hi),
                            frame.layers[S3D_LAYER_WORLD].projection, tileHasFirstPerson == 0u))
        atomicOr(tileLightBits[index >> 5], 1u << (index & 31u));
    }
  }
  barrier();

  // 3. The mask as a list: each culled-in light at its rank among them (light order, so the shadowed lights,
  // which the light buffer holds first, come first), stored for the lighting pass's lit tiles.
  uint count = 0u, shadowed = 0u;
  for (uint w = 0u; w < S3D_LIGHT_MASK_WORDS; ++w) {
    count += bitCount(tileLightBits[w]);
    shadowed += bitCount(tileLightBits[w] & bitsBelow(int(lighting.shadowedLights) - int(w) * 32));
  }
  uint list = tileLightList(tile);
  if (count > 0u) {
    for (uint index = local; index < lighting.lightCount; index += kThreads) {
      uint word = index >> 5, bit = 1u << (index & 31u);
      uint rank = bitCount(tileLightBits[word] & (bit - 1u));
      for (uint w = 0u; w < S3D_LIGHT_MASK_WORDS; ++w) rank += w < word ? bitCount(tileLightBits[w]) : 0u;
      if ((tileLightBits[word] & bit) != 0u) atomicOr(tileLightIndices[rank >> 2], index << ((rank & 3u) * 8u));
    }
    barrier();
    for (uint w = local; w < (count + 3u) / 4u; w += kThreads) tileEntries[list + 1u + w] = tileLightIndices[w];
  }

  // 4. The tile into its class's list.
  if (local != 0u) return;
  tileEntries[list] = count | (shadowed << 16);
  uint tileClass = !surfaces      ? S3D_TILE_SKY
                  : count == 0u   ? S3D_TILE_UNLIT
                  : shadowed > 0u ? S3D_TILE_LIT_SHADOWED
                                  : S3D_TILE_LIT;
  uint slot = atomicAdd(tileHeader.tileClassDispatch[tileClass].x, 1u);
  tileEntries[tileClassList(tileClass) + slot] = packTile(tile);
}
