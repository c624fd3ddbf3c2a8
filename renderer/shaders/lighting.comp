#version 450
// Tiled deferred lighting (section 4.3.3), after light_tiles.comp culled each tile's lights into its light list
// and listed the tile by class: per tile of S3D_TILE_SIZE^2 render pixels (one thread each), each pixel gets
// hemisphere ambient x ambient occlusion (depth-aware upsample of the half-resolution image), the sun through
// its cascaded shadow maps (the deferred shadow mask, fused here), the tile's local lights with their shadow
// maps (in light order), and its material (albedo on diffuse, Schlick Fresnel on specular), or the sky's
// colour. One variant per tile class (S3D_TILE_*): sky tiles compute the sky only, unlit tiles no light loop,
// lit tiles without shadowed lights no shadow-map lookup.
// Writes HDR colour; in a frame without transparent surfaces or supersampling it resolves in place instead (the
// resolve's outputs, one full-screen pass fewer). A masked render shades only shade-mask pixels of its tiles.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "tonemap.glsl"

layout(local_size_x = S3D_TILE_SIZE, local_size_y = S3D_TILE_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform sampler2D normalGlossiness;
layout(binding = 3) uniform usampler2D material;           // packMaterial: albedo, object index
layout(binding = 4) uniform sampler2D ambientOcclusion;    // half resolution: occlusion, linear depth
layout(binding = 5) uniform sampler2DShadow sunAtlas;      // compare LESS_OR_EQUAL, bilinear: 2x2 PCF per tap
layout(binding = 6) uniform sampler2DShadow localShadowAtlas;
layout(binding = 7) uniform Shadows { ShadowConstants shadow; };
layout(std430, binding = 8) readonly buffer Objects { ObjectConstants objects[]; };
layout(std430, binding = 9) readonly buffer Lights { LightConstants lights[]; };
layout(binding = 10, rgba16f) uniform writeonly image2D hdrColor;      // render size
layout(binding = 13, rgba8) uniform writeonly image2D displayColor;   // the resolve's outputs (output size)
layout(binding = 14, rgba16f) uniform writeonly image2D resolvedHdrColor;
layout(binding = 15, r32f) uniform writeonly image2D linearDepthImage;
#define S3D_TILES_BINDING 11
#define S3D_SHADE_MASK_BINDING 12
#include "tiles.glsl"
#include "surface.glsl"
layout(push_constant) uniform Push { LightingConstants lighting; };
// Whether the frame has sun cascades: without, their lookup is compiled out.
layout(constant_id = 2) const bool kSunShadows = true;
// Whether this pass writes the resolve's outputs itself (no transparent pass and no supersampling follow).
layout(constant_id = 4) const bool kResolveInPlace = false;
// The tile class this variant shades: sky tiles (constant 5), lit tiles (6), lit tiles some of whose lights have
// shadow maps (6 and 3: only they run the shadowed lights' loop), or none of these: unlit tiles.
layout(constant_id = 5) const bool kSkyTiles = false;
layout(constant_id = 6) const bool kLitTiles = false;
layout(constant_id = 3) const bool kShadowedLightTiles = false;


// Sky at infinite distance: its colour depends on the view direction only.
vec3 skyColor(ivec2 pixel) {
  vec2 ndc = (vec2(pixel) + 0.5) * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[S3D_LAYER_WORLD].projection;
  vec3 viewDirection = vec3((ndc.x + p.z) / p.x, (ndc.y + p.w) / p.y, -1.0);
  vec3 direction = normalize(mat3(frame.layers[S3D_LAYER_WORLD].worldFromView) * viewDirection);
  return direction.y >= 0.0 ? mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, sqrt(direction.y))
                            : mix(frame.skyHorizon.rgb, frame.skyGround.rgb, sqrt(-direction.y));
}

// Depth-aware upsample: the half-resolution texel i sits on render pixel 2i, so an even coordinate takes its
// texel and an odd one the two around it (four taps, the unused ones weighted 0), each weighted by its depth's
// nearness (ambientDepthWeight); where none is near (a thin feature) the nearest in depth.
float upsampledOcclusion(ivec2 pixel, float linearDepth) {
  ivec2 base = pixel >> 1;
  ivec2 odd = pixel & 1;
  ivec2 last = ivec2(frame.ambientOcclusion.yz) - 1;
  float sum = 0.0, weightSum = 0.0, nearestGap = S3D_INFINITY, nearest = 1.0;
  for (int tap = 0; tap < 4; ++tap) {
    ivec2 offset = ivec2(tap & 1, tap >> 1);
    vec2 texel = texelFetch(ambientOcclusion, min(base + offset * odd, last), 0).rg;
    float used = all(lessThanEqual(offset, odd)) ? 1.0 : 0.0;
    float weight = used * ambientDepthWeight(texel.y, linearDepth);
    sum += weight * texel.x;
    weightSum += weight;
    float gap = used > 0.0 ? abs(texel.y - linearDepth) : S3D_INFINITY;
    if (gap < nearestGap) {
      nearestGap = gap;
      nearest = texel.x;
    }
  }
  return weightSum > 1e-3 ? sum / weightSum : nearest;
}

// 2x2 bilinear compare taps half a texel off the centre: a tent-weighted 3x3-texel percentage-closer filter.
float pcf(sampler2DShadow atlas, vec2 atlasUv, vec2 texel, float receiverDepth) {
  float lit = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) lit += textureLod(atlas, vec3(atlasUv + (vec2(x, y) - 0.5) * texel, receiverDepth), 0.0);
  return lit * 0.25;
}

// The sun's share reaching a point (seed 003 8.5.3.6, 000 4.3.3): the first cascade that contains it (the one
// with the most texels per metre), the point moved one texel along its normal against acne. The loop only
// finds the cascade, so the filter runs once.
float sunShadow(vec3 position, vec3 normal) {
  int count = int(shadow.sunShadow.x);
  vec3 found = vec3(0.0);  // atlas uv, receiver depth
  bool inCascade = false;
  for (int cascade = 0; cascade < count && !inCascade; ++cascade) {
    vec4 params = shadow.cascadeParams[cascade];
    vec3 clip = (shadow.cascadeViewProjection[cascade] * vec4(position + normal * params.x, 1.0)).xyz;  // ortho
    vec2 uv = clip.xy * 0.5 + 0.5;
    vec4 rect = shadow.cascadeAtlasRect[cascade];
    vec2 margin = 2.0 * shadow.sunShadow.yz / rect.zw;  // the PCF footprint stays inside the cascade
    inCascade = all(greaterThanEqual(uv, margin)) && all(lessThanEqual(uv, 1.0 - margin)) && clip.z <= 1.0;
    // A cascade without casters leaves the point lit: a receiver depth no map texel can be behind.
    if (inCascade) found = vec3(rect.xy + uv * rect.zw, params.y > 0.5 ? clip.z - params.z : -1.0);
  }
  if (!inCascade) return 1.0;  // beyond the last cascade: lit
  return pcf(sunAtlas, found.xy, shadow.sunShadow.yz, found.z);
}

// Point and spot shadows (seed 000 4.3.3). A point light is six 90-degree views (Crytek's "six projected light
// sources"): the dominant axis of the light-to-point vector picks the face.
float localShadow(LightConstants light, vec3 position, vec3 normal) {
  vec3 fromLight = position - light.positionRadius.xyz;
  int view = light.shadowView;
  if (light.kind == S3D_LIGHT_POINT) {
    vec3 a = abs(fromLight);
    if (a.x >= a.y && a.x >= a.z) view += fromLight.x >= 0.0 ? 0 : 1;
    else if (a.y >= a.z) view += fromLight.y >= 0.0 ? 2 : 3;
    else view += fromLight.z >= 0.0 ? 4 : 5;
  }
  // Normal offset of 1.5 texels at this distance against acne; the map holds back faces (seed 000 4.3.3).
  vec3 receiver = position + normal * (1.5 * shadow.localParams[view].x * length(fromLight));
  vec4 clip = shadow.localViewProjection[view] * vec4(receiver, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  vec4 rect = shadow.localAtlasRect[view];
  vec2 texel = shadow.localShadow.xy;
  vec2 uv = clamp(ndc.xy * 0.5 + 0.5, 1.5 * texel / rect.zw, 1.0 - 1.5 * texel / rect.zw);
  return pcf(localShadowAtlas, rect.xy + uv * rect.zw, texel, ndc.z);
}

// One point or spot light's diffuse and specular light at a surface point (its shadow map looked up when
// `shadowed`).
void addLight(LightConstants light, bool shadowed, vec3 position, vec3 normal, vec3 toEye, float exponent,
              inout vec3 diffuse, inout vec3 specular) {
  vec3 offset = light.positionRadius.xyz - position;
  float distanceToLight = length(offset);
  vec3 toLight = offset / max(distanceToLight, 1e-6);
  float nDotL = max(dot(normal, toLight), 0.0);
  vec3 radiance = light.color.rgb * pointLightFalloff(distanceToLight, light.positionRadius.w);
  if (light.kind == S3D_LIGHT_SPOT)
    radiance *= spotConeFalloff(dot(-toLight, light.spotDirection.xyz), light.spotCone.x, light.spotCone.y);
  if (shadowed && nDotL > 0.0 && max(radiance.r, max(radiance.g, radiance.b)) > 0.0)
    radiance *= localShadow(light, position, normal);
  diffuse += radiance * nDotL;
  specular += radiance * (nDotL * normalizedBlinnPhong(dot(normal, normalize(toLight + toEye)), exponent));
}

// The lit colour of a surface pixel: ambient, sun and the tile's lights, accumulated as diffuse and specular
// light (normalized Blinn-Phong), then albedo and Fresnel applied.
vec3 shadeSurface(ivec2 pixel, Surface s, uint lightList) {
  vec4 normalAndGloss = texelFetch(normalGlossiness, pixel, 0);
  vec3 normal = normalize(normalAndGloss.xyz);
  float exponent = blinnPhongExponent(normalAndGloss.w);
  vec3 toEye = normalize(s.eye - s.position);

  float occlusion = frame.options.y != 0u && s.layer == S3D_LAYER_WORLD ? upsampledOcclusion(pixel, s.linearDepth) : 1.0;
  vec3 diffuse = frame.ambientColor.rgb * (normal.y * 0.7 + 0.3) * occlusion;  // hemisphere ambient, Y up
  vec3 specular = vec3(0.0);

  vec3 toSun = frame.directionToSun.xyz;
  float sunDotN = max(dot(normal, toSun), 0.0);
  if (sunDotN > 0.0) {
    vec3 radiance = frame.sunColor.rgb;
    if (kSunShadows) radiance *= sunShadow(s.position, normal);
    diffuse += radiance * sunDotN;
    specular += radiance * (sunDotN * normalizedBlinnPhong(dot(normal, normalize(toSun + toEye)), exponent));
  }

  // Loops over the tile's list, its shadowed lights first (a CPU rasterizer runs a loop body at least once
  // and both sides of every branch, so the lists are compact, unshadowed lights skip the shadow code, and tiles
  // without shadowed lights or without any light have variants without those loops).
  if (kLitTiles) {
    uint counts = tileEntries[lightList];  // lights, shadowed lights << 16
    uint shadowedCount = counts >> 16;
    if (kShadowedLightTiles)
      for (uint n = 0u; n < shadowedCount; ++n)
        addLight(lights[listedLight(lightList, n)], true, s.position, normal, toEye, exponent, diffuse, specular);
    for (uint n = kShadowedLightTiles ? shadowedCount : 0u; n < (counts & 0xffffu); ++n)
      addLight(lights[listedLight(lightList, n)], false, s.position, normal, toEye, exponent, diffuse, specular);
  }

  uvec2 stored = texelFetch(material, pixel, 0).rg;
  uint objectIndex = unpackObjectIndex(stored);
  vec3 f0 = objects[objectIndex].specular.rgb;
  vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(dot(normal, toEye), 0.0, 1.0), 5.0);  // Schlick
  // Emission comes from the object's constants: the G-buffer carries no emissive texture, so no extra target.
  return unpackAlbedo(stored) * diffuse + fresnel * specular + objects[objectIndex].emissive.rgb;
}

void main() {
  uint tileClass = kSkyTiles              ? S3D_TILE_SKY
                  : kShadowedLightTiles ? S3D_TILE_LIT_SHADOWED
                  : kLitTiles           ? S3D_TILE_LIT
                                        : S3D_TILE_UNLIT;
  ivec2 tile = classTile(tileClass);
  ivec2 pixel = tile * S3D_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  bool shaded = all(lessThan(pixel, ivec2(frame.screen.xy))) && shadeMasked(pixel);

  if (!shaded) return;
  float device = texelFetch(deviceDepth, pixel, 0).r;
  // A sky tile's shaded pixels are all sky (light_tiles.comp found no surface among them).
  bool sky = kSkyTiles || isSkyDeviceDepth(frame.linearDepth, device);
  Surface surface;
  vec3 shadedColor;
  if (kSkyTiles) {
    surface.layer = S3D_LAYER_WORLD;
    shadedColor = skyColor(pixel);
  } else {
    surface = surfaceAt(pixel, device);
    shadedColor = sky ? skyColor(pixel) : shadeSurface(pixel, surface, tileLightList(tile));
  }
  vec4 color = vec4(shadedColor, 1.0);
  if (kResolveInPlace) {
    // As resolve.comp does with one sample, but from the unrounded colour: Vulkan leaves the rounding of a
    // float16 image store to the implementation (lavapipe truncates), so the HDR output gets the store's own.
    color = finiteHdr(color);
    // Seed 4.6.2: the weapon mask rides in alpha (0 on the first-person layer), see resolve.comp.
    float weapon = !sky && surface.layer == S3D_LAYER_FIRST_PERSON ? 1.0 : 0.0;
    imageStore(displayColor, pixel, vec4(encodeSrgb(filmic(color.rgb * frame.exposure.x)), 1.0 - weapon));
    imageStore(resolvedHdrColor, pixel, color);
    imageStore(linearDepthImage, pixel, vec4(stereoDepthFromDevice(frame.linearDepth, device)));
  } else {
    imageStore(hdrColor, pixel, color);
  }
  countShaded(S3D_COUNT_LIGHTING, 1u);
}
