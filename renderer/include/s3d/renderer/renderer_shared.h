// Frame, object and light constants of the deferred renderer, shared by C++ and GLSL so no field can drift.
#ifndef S3D_RENDERER_SHARED_H
#define S3D_RENDERER_SHARED_H

#include "s3d/gpu/linear_depth.h"
#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_LAYER_WORLD 0
#define S3D_LAYER_FIRST_PERSON 1
#define S3D_LIGHT_POINT 1
#define S3D_LIGHT_SPOT 2
#define S3D_COMPUTE_GROUP_SIZE 8

// Tiles: the lighting pass shades one tile of S3D_TILE_SIZE^2 render pixels per workgroup, one thread per
// pixel; the half-resolution ambient occlusion covers the same tile with one 8x8 group of its texels.
#define S3D_TILE_SIZE 16
#define S3D_TILE_RESET_GROUP_SIZE 256  // tile_reset.comp: one flag word per invocation
#define S3D_MAX_LIGHTS 256  // point and spot lights of a scene: one bit each in a tile's light mask
#define S3D_LIGHT_MASK_WORDS (S3D_MAX_LIGHTS / 32)
// A tile's light list: a word with the count of its lights and (bits 16-31) of its shadowed ones, then the lights'
// indices, one byte each, four to a word, in light order (so S3D_MAX_LIGHTS <= 256).
#define S3D_LIGHT_LIST_WORDS (1 + S3D_MAX_LIGHTS / 4)

// Slots of the shaded-pixel counters (RendererOptions::countShadedPixels).
#define S3D_COUNT_GBUFFER 0   // render pixels the G-buffer wrote
#define S3D_COUNT_SSAO 1      // half-resolution texels the ambient occlusion computed
#define S3D_COUNT_SSAO_BLUR 2 // half-resolution texels the blur wrote
#define S3D_COUNT_LIGHTING 3  // render pixels lit (surfaces) or given the sky
#define S3D_COUNT_RESOLVE 4   // output pixels resolved
#define S3D_COUNT_SLOTS 8

// Per layer (world, first-person): how its geometry is projected and how its depth is turned back into a
// world position (the seed's "linearly transform the screen-space VPos basis to the target space").
struct LayerConstants {
  mat4 viewProjection;  // layer space (world, or camera space for first-person) -> clip
  mat4 worldFromView;   // the layer's view space -> world
  vec4 projection;      // P[0][0], P[1][1], P[2][0], P[2][1]: view position from linear depth, off-axis aware
};

struct FrameConstants {  // uniform buffer, std140 (every member 16-byte aligned)
  LayerConstants layers[2];
  LinearDepthParams linearDepth;
  vec4 directionToSun;  // world, unit
  vec4 sunColor;
  vec4 ambientColor;  // hemisphere ambient: ambient * (N.y * 0.7 + 0.3)
  vec4 skyZenith;
  vec4 skyHorizon;
  vec4 skyGround;
  vec4 screen;  // width, height, 1 / width, 1 / height
  vec4 exposure;  // x: exposure multiplier
  vec4 ambientOcclusion;  // x: radius in world units; y, z: half-resolution width, height
  vec4 worldViewDepth;    // view depth of a world point p in the world layer's view: dot(worldViewDepth, (p, 1))
  uvec4 tiles;    // x, y: tiles per row and column; z: a masked render's shade-mask value from which a pixel is shaded
  uvec4 options;  // x: supersample factor, y: 1 = ambient occlusion on, z, w: visibility ids (packVisibility)
};

#define S3D_SSAO_SAMPLES 16

// Weight of a half-resolution ambient-occlusion texel for a surface at linear depth `depth` (blur and
// upsample): 1 at the same depth, falling to 0 at 10 % apart (+inf, sky and weapon texels: 0).
S3D_INLINE float ambientDepthWeight(float texelDepth, float depth) {
  return max(0.0f, 1.0f - abs(texelDepth - depth) / (0.1f * depth));
}

struct ObjectConstants {  // storage buffer, std430, one per object
  mat4 objectToLayer;  // world layer: object -> world; first-person: object -> camera space
  mat4 objectToWorld;  // for lighting and Fresnel
  mat4 normalToWorld;  // inverse transpose of objectToWorld
  vec4 albedo;         // linear diffuse reflectance
  vec4 specular;       // rgb: F0, a: glossiness
  uint layer;
  float normalScale;   // tangent-space normal map x/y scale; 0: no normal map (the interpolated normal as is)
  uint firstIndex;     // its mesh in the scene's index buffer: first index, and the vertex its indices count from
  uint vertexOffset;
  vec4 baseColorUv;    // base-colour texture transform (Material::baseColorTransform): rows of its 2x2 part
  vec4 normalUv;       // the normal map's, likewise
  vec4 uvOffsets;      // xy: base-colour transform offset, zw: the normal map's
  vec4 emissive;       // rgb: emitted radiance (Material::emissive); a: alpha cutoff (0: not a cut-out)
  // What the compute G-buffer resolve samples for a ray-cast pixel (surface_texels.glsl): x the base-colour
  // texture, y the normal map (Scene::textures indices, S3D_NO_TEXTURE: none); z 1: double-sided.
  uvec4 surfaceTextures;
};
#define S3D_NO_TEXTURE 0xffffffffu
// albedo.a holds the opacity of transparent objects and the coverage alpha (Material::cutoutAlpha) of cut-outs.

// A texture transform packed as ObjectConstants holds it: rows (r0.x, r0.y; r1.x, r1.y) of T*R*S's 2x2 part
// in `rows` (x y z w), its translation in `offset`.
S3D_INLINE vec2 transformTexCoord(vec4 rows, vec2 offset, vec2 uv) {
  return vec2(rows.x * uv.x + rows.y * uv.y, rows.z * uv.x + rows.w * uv.y) + offset;
}

// Whether a cut-out fragment is dropped: its coverage alpha (the material's alpha x the texel's) is below the
// cutoff. A cutoff of 0 keeps every fragment.
S3D_INLINE bool cutOut(float materialAlpha, float texelAlpha, float cutoff) { return materialAlpha * texelAlpha < cutoff; }

// Per-vertex surface parameterization: the renderer's second vertex stream (zeros for meshes without it).
struct SurfaceVertex {
  vec2 texCoord;
  vec4 tangent;  // xyz: +u direction in object space, w: handedness (+-1)
};

// A point or spot light, as the lighting pass reads it (storage buffer, std430).
struct LightConstants {
  vec4 positionRadius;   // world position, radius of influence
  vec4 viewPosition;     // xyz: position in the world layer's view space (tile culling)
  vec4 color;            // linear radiance scale
  vec4 spotDirection;    // spot light: unit direction it points to (world)
  vec4 spotCone;         // spot light: x cos(outer cone angle), y cos(inner cone angle)
  uint kind;             // S3D_LIGHT_*
  int shadowView;        // -1: unshadowed; point: first of six atlas views; spot: its view
  uint padding1;
  uint padding2;
};

struct LightingConstants {  // push constants of the lighting pass
  uint lightCount;
  uint shadowedLights;  // lights [0, shadowedLights) have shadow maps this frame, the rest not
  uint padding1;
  uint padding2;
};

// The lighting pass's tile classes (light_tiles.comp): each shaded by a variant compiled for it, as a CPU
// rasterizer runs every branch and a loop body at least once.
#define S3D_TILE_SKY 0      // no shaded surface pixel: the sky's colour only
#define S3D_TILE_UNLIT 1    // surfaces, no point or spot light reaches them
#define S3D_TILE_LIT 2      // surfaces and the lights of the tile's light list, none with a shadow map
#define S3D_TILE_LIT_SHADOWED 3  // surfaces and the lights of the tile's light list, some with a shadow map
#define S3D_TILE_CLASSES 4

// Head of the tile buffer (std430), followed by uint entries, tilesX * tilesY each (a tile packed as x | y << 16):
// the tile flags of the ambient-occlusion region, the masked tiles, the ambient-occlusion tiles, the tiles of
// each lighting class (S3D_TILE_CLASSES lists), then S3D_LIGHT_LIST_WORDS words per tile (its light list).
struct TileHeader {
  uvec4 lightingDispatch;  // vkCmdDispatchIndirect arguments: x = masked tiles
  uvec4 ambientDispatch;   // x = tiles of the ambient-occlusion region (masked tiles and their 8 neighbours)
  uint shadedPixels[S3D_COUNT_SLOTS];
  uvec4 tileClassDispatch[S3D_TILE_CLASSES];  // x = tiles of each lighting class
};
#define S3D_TILE_LIST_WORDS (3 + S3D_TILE_CLASSES + S3D_LIGHT_LIST_WORDS)  // entries per tile, all lists

// Push constants of the resolve pass: the G-buffer and lighting run at supersample x the output size; the
// resolve averages each output pixel's supersample^2 samples (colour after tone mapping) and keeps the
// nearest of their linear depths, so a pixel half-covered by an occluder moves with the occluder.
struct ResolveConstants {
  int supersample;  // 1: no supersampling
  int outputWidth;
  int outputHeight;
  int padding0;
};

// Push constants of the transparent pass (transparent.comp), one dispatch per transparent object, farthest
// first: the object's triangles composited over the lit HDR image in the render tiles its bounds cover.
struct TransparentConstants {
  uvec4 tileRect;         // xy: the object's first render tile, zw: one past its last
  vec2 depthRange;        // the world layer's viewport depth range (Listing 4.3): min, max device depth
  uint objectIndex;
  uint triangleCount;
  uint reversedZ;         // 1: nearer surfaces have greater device depth
  uint initializesCoverage;  // 1: the dispatch runs over every tile (else over tileRect) and writes all coverage
  uint masked;               // 1: only pixels the shade mask shades are composited (frame.tiles.z, as the lighting)
  uint padding1;
};

// Whether a light can reach a tile (the lighting pass's culling, tested against brute force in C++): its
// sphere (centre in the world layer's view space, radius) must overlap the view-depth range of the tile's
// surface points and, when sidePlanes, the wedge between the rays through the tile's edges (ndcRect: x0, y0,
// x1, y1 in the world layer's normalized device coordinates; projection: P00, P11, P20, P21). A tile with
// first-person pixels passes sidePlanes false: those were projected by the first-person projection.
S3D_INLINE bool sphereTouchesTile(vec3 centre, float radius, vec2 depthRange, vec4 ndcRect, vec4 projection,
                                  bool sidePlanes) {
  float depth = -centre.z;
  if (depth + radius < depthRange.x || depth - radius > depthRange.y) return false;
  if (!sidePlanes) return true;
  // A view point lies on the ray of ndc x where X = k d, k = (x + P20) / P00 (d = -Z), i.e. on the plane
  // X + k Z = 0; the tile lies between its two edges' planes (likewise for y).
  float kx0 = (ndcRect.x + projection.z) / projection.x;
  float kx1 = (ndcRect.z + projection.z) / projection.x;
  float ky0 = (ndcRect.y + projection.w) / projection.y;
  float ky1 = (ndcRect.w + projection.w) / projection.y;
  float kxLo = min(kx0, kx1), kxHi = max(kx0, kx1), kyLo = min(ky0, ky1), kyHi = max(ky0, ky1);
  if (centre.x + kxLo * centre.z < -radius * sqrt(1.0f + kxLo * kxLo)) return false;
  if (centre.x + kxHi * centre.z > radius * sqrt(1.0f + kxHi * kxHi)) return false;
  if (centre.y + kyLo * centre.z < -radius * sqrt(1.0f + kyLo * kyLo)) return false;
  if (centre.y + kyHi * centre.z > radius * sqrt(1.0f + kyHi * kyHi)) return false;
  return true;
}

// Shadows (seed 003 section 8.5.3, 000 section 4.3.3): sun cascades in one depth atlas, point (six views) and
// spot (one view) shadow maps in a second atlas, both read by the lighting pass.
#define S3D_MAX_SUN_CASCADES 4
#define S3D_MAX_LOCAL_SHADOW_VIEWS 48

struct ShadowConstants {  // uniform buffer, std140
  mat4 cascadeViewProjection[S3D_MAX_SUN_CASCADES];  // world -> cascade clip (x, y in -1..1, z in 0..1)
  vec4 cascadeAtlasRect[S3D_MAX_SUN_CASCADES];       // the cascade's tile in atlas uv: offset xy, size zw
  vec4 cascadeParams[S3D_MAX_SUN_CASCADES];          // x: world size of a texel, y: 1 when rendered (else lit)
  vec4 sunShadow;  // x: cascade count, y: 1 / atlas width, z: 1 / atlas height, w: receiver depth bias
  mat4 localViewProjection[S3D_MAX_LOCAL_SHADOW_VIEWS];  // world -> clip of each point-light face / spot light
  vec4 localAtlasRect[S3D_MAX_LOCAL_SHADOW_VIEWS];       // offset xy, size zw in atlas uv
  vec4 localParams[S3D_MAX_LOCAL_SHADOW_VIEWS];          // x: texel size per metre of distance (2 tan(fov/2) / tile)
  vec4 localShadow;  // x: 1 / atlas width, y: 1 / atlas height
};

// Glossiness 0..1 -> Blinn-Phong exponent 2..2048.
S3D_INLINE float blinnPhongExponent(float glossiness) { return exp2(10.0f * glossiness + 1.0f); }

// Normalized Blinn-Phong: (n + 8) / 8 keeps the reflected energy roughly constant as the lobe narrows
// (the 1/pi of both diffuse and specular is folded into the light colors).
S3D_INLINE float normalizedBlinnPhong(float nDotH, float exponent) {
  return (exponent + 8.0f) / 8.0f * pow(max(nDotH, 0.0f), exponent);
}

// Point-light falloff reaching exactly zero at the radius.
S3D_INLINE float pointLightFalloff(float distanceToLight, float radius) {
  float ratio = min(distanceToLight / radius, 1.0f);
  float window = 1.0f - ratio * ratio;
  return window * window / (1.0f + distanceToLight * distanceToLight);
}

// Spot light cone: 1 inside the inner cone, 0 outside the outer one, a smooth ramp between.
S3D_INLINE float spotConeFalloff(float cosAngle, float cosOuter, float cosInner) {
  float t = min(max((cosAngle - cosOuter) / max(cosInner - cosOuter, 1e-4f), 0.0f), 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The G-buffer's material target (RG32_UINT): linear albedo (base colour x texture) in 16-bit unorm per channel
// (error under 8e-6) and the object's index (16 bits), whose constants give F0; packed with plain arithmetic, so a CPU
// rasterizer pays no transcendental per fragment.
#define S3D_NO_OBJECT 0xffffu  // the object index where nothing was drawn (so at most 65535 objects)
S3D_INLINE uint unorm16(float value) { return uint(min(max(value, 0.0f), 1.0f) * 65535.0f + 0.5f); }
S3D_INLINE uvec2 packMaterial(vec3 albedo, uint objectIndex) {
  return uvec2(unorm16(albedo.x) | (unorm16(albedo.y) << 16), unorm16(albedo.z) | (objectIndex << 16));
}
S3D_INLINE vec3 unpackAlbedo(uvec2 material) {
  return vec3(float(material.x & 0xffffu), float(material.x >> 16), float(material.y & 0xffffu)) / 65535.0f;
}
S3D_INLINE uint unpackObjectIndex(uvec2 material) { return material.y >> 16; }

// The visibility target of the G-buffer pass: which triangle of which object each pixel shows, so the raster
// pass writes 4 bytes a pixel and the G-buffer resolve (compute) evaluates the surface. Narrow ids (R32_UINT)
// hold triangle << objectBits | object; a scene whose object count and largest mesh do not fit 32 bits that way
// gets wide ids (R32G32_UINT: object, triangle). frame.options.z: objectBits, w: 1 for wide ids. Objects whose
// G-buffer the raster pass writes itself (textured ones) write S3D_RASTER_SHADED, never a valid id.
#define S3D_RASTER_SHADED 0xffffffffu
S3D_INLINE uvec2 packVisibility(uint objectIndex, uint triangle, uvec4 options) {
  return options.w != 0u ? uvec2(objectIndex, triangle) : uvec2((triangle << options.z) | objectIndex, 0u);
}
S3D_INLINE uint unpackVisibilityObject(uvec2 id, uvec4 options) {
  return options.w != 0u ? id.x : id.x & ((1u << options.z) - 1u);
}
S3D_INLINE uint unpackVisibilityTriangle(uvec2 id, uvec4 options) { return options.w != 0u ? id.y : id.x >> options.z; }
#ifdef __cplusplus
// The packing of a scene's ids (options z, w): narrow when triangle << objectBits | object fits 32 bits with the
// all-ones value to spare for S3D_RASTER_SHADED (mostTriangles: the largest mesh's triangle count).
inline uvec2 visibilityPacking(std::uint64_t objectCount, std::uint64_t mostTriangles) {
  uint objectBits = 0;
  while (objectBits < 32 && (std::uint64_t(1) << objectBits) < objectCount) ++objectBits;
  const bool narrow = objectBits < 32 && mostTriangles < (std::uint64_t(1) << (32 - objectBits));
  return {objectBits, narrow ? 0u : 1u};
}
#endif

S3D_GPU_END

#endif  // S3D_RENDERER_SHARED_H
