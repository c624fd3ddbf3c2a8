// Frame, object and light constants of the deferred renderer, shared by C++ and GLSL so no field can drift.
#ifndef S3D_RENDERER_SHARED_H
#define S3D_RENDERER_SHARED_H

#include "s3d/gpu/linear_depth.h"
#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_LAYER_WORLD 0
#define S3D_LAYER_FIRST_PERSON 1
#define S3D_LIGHT_AMBIENT_AND_SUN 0
#define S3D_LIGHT_POINT 1
#define S3D_LIGHT_SPOT 2
#define S3D_COMPUTE_GROUP_SIZE 8

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
  vec4 ambientOcclusion;  // x: radius in world units
};

#define S3D_SSAO_SAMPLES 16

struct ObjectConstants {  // storage buffer, std430, one per object
  mat4 objectToLayer;  // world layer: object -> world; first-person: object -> camera space
  mat4 objectToWorld;  // for lighting and Fresnel
  mat4 normalToWorld;  // inverse transpose of objectToWorld
  vec4 albedo;         // linear diffuse reflectance
  vec4 specular;       // rgb: F0, a: glossiness
  uint layer;
  float normalScale;   // tangent-space normal map x/y scale; 0: no normal map (the interpolated normal as is)
  uint padding1;
  uint padding2;
};

// Per-vertex surface parameterization: the renderer's second vertex stream (zeros for meshes without it).
struct SurfaceVertex {
  vec2 texCoord;
  vec4 tangent;  // xyz: +u direction in object space, w: handedness (+-1)
};

struct LightConstants {  // push constants of the light-accumulation pass
  vec4 positionRadius;   // point/spot light: world position, radius of influence
  vec4 color;            // linear radiance scale
  vec4 spotDirection;    // spot light: unit direction it points to (world)
  vec4 spotCone;         // spot light: x cos(outer cone angle), y cos(inner cone angle)
  uint kind;             // S3D_LIGHT_*
  int shadowView;        // -1: unshadowed; sun: reads the shadow mask; point: first of six atlas views; spot: its view
  uint padding1;
  uint padding2;
};

// Push constants of the resolve pass: the G-buffer and lights run at supersample x the output size; the
// resolve averages each output pixel's supersample^2 samples (colour after tone mapping) and keeps the
// nearest of their linear depths, so a pixel half-covered by an occluder moves with the occluder.
struct ResolveConstants {
  int supersample;  // 1: no supersampling
  int outputWidth;
  int outputHeight;
  int padding0;
};

// Shadows (seed 003 section 8.5.3, 000 section 4.3.3): sun cascades in one depth atlas, read by the deferred
// shadow-mask pass; point (six views) and spot (one view) shadow maps in a second atlas, read by the light pass.
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

S3D_GPU_END

#endif  // S3D_RENDERER_SHARED_H
