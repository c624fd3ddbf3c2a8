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
  uint padding0;
  uint padding1;
  uint padding2;
};

struct LightConstants {  // push constants of the light-accumulation pass
  vec4 positionRadius;   // point light: world position, radius of influence
  vec4 color;            // linear radiance scale
  uint kind;             // S3D_LIGHT_*
  uint padding0;
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

S3D_GPU_END

#endif  // S3D_RENDERER_SHARED_H
