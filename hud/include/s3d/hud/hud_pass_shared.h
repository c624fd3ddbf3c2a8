// The HUD pass's push constants and its per-pixel blend, shared by the shader and the C++ reference, so the GPU
// and hud::compositeLayer compute the same float operations in the same order.
#ifndef S3D_HUD_HUD_PASS_SHARED_H
#define S3D_HUD_HUD_PASS_SHARED_H

#include "s3d/gpu/shared.h"

#ifdef __cplusplus
#define S3D_HUD_PRECISE
#else
#define S3D_HUD_PRECISE precise  // no fused multiply-add: the C++ reference rounds the product and the sum apart
#endif

S3D_GPU_BEGIN

#define S3D_HUD_GROUP_SIZE 8
#define S3D_HUD_MAX_ELEMENTS 16  // per pass: bounds the barriers record() makes without allocating

// One element layer over both eyes: the layer's top-left pixel lands at leftOrigin / rightOrigin (eye pixels).
struct HudCompositeConstants {
  int leftOriginX;
  int leftOriginY;
  int rightOriginX;
  int rightOriginY;
  int layerWidth;
  int layerHeight;
  int eyeWidth;
  int eyeHeight;
  int behindWeapon;  // 1: the element lies behind the weapon and fades where the eye's alpha (the mask) is < 255
};

// Round half up for values >= 0 (std::lround there); x - floor(x) is exact, so no tie is lost to an addition.
S3D_INLINE float hudRoundHalfUp(float x) {
  float whole = floor(x);
  return x - whole >= 0.5f ? whole + 1.0f : whole;
}

// The element's opacity at an eye pixel, from 8-bit levels (0..255 as floats): the layer's alpha, times the eye's
// alpha where the element is behind the weapon and the weapon mask covers the pixel (seed 4.6.2's fade).
S3D_INLINE float hudOpacity(float layerAlpha, float eyeAlpha, int behindWeapon) {
  S3D_HUD_PRECISE float opacity = layerAlpha / 255.0f;
  if (behindWeapon != 0 && eyeAlpha < 255.0f) opacity = opacity * (eyeAlpha / 255.0f);
  return opacity;
}

// One colour channel of the layer over the eye (8-bit levels as floats), rounded to a level.
S3D_INLINE float hudBlendChannel(float eye, float layer, float opacity) {
  S3D_HUD_PRECISE float blended = eye + (layer - eye) * opacity;
  return hudRoundHalfUp(blended);
}

S3D_GPU_END

#endif  // S3D_HUD_HUD_PASS_SHARED_H
