#version 450
// Light accumulation (section 4.3.3): HDR diffuse and specular light per pixel, additive per light.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform sampler2D normalGlossiness;
layout(binding = 3) uniform sampler2D ambientOcclusion;  // 1 everywhere when SSAO is off
layout(binding = 4) uniform sampler2D sunShadowMask;     // read only when light.shadowView >= 0
layout(binding = 5) uniform sampler2DShadow localShadowAtlas;  // point-light faces and spot views
layout(binding = 6) uniform Shadows { ShadowConstants shadow; };
layout(push_constant) uniform Push { LightConstants light; };

// Point and spot shadows are looked up here, in the light's own pass (seed 000 4.3.3). A point light is six
// 90-degree views (Crytek's "six projected light sources"): the dominant axis of the light-to-point vector
// picks the face. 2x2 bilinear compare taps half a texel apart: a 3x3-texel PCF.
float localShadow(vec3 worldPosition, vec3 normal) {
  vec3 fromLight = worldPosition - light.positionRadius.xyz;
  int view = light.shadowView;
  if (light.kind == S3D_LIGHT_POINT) {
    vec3 a = abs(fromLight);
    if (a.x >= a.y && a.x >= a.z) view += fromLight.x >= 0.0 ? 0 : 1;
    else if (a.y >= a.z) view += fromLight.y >= 0.0 ? 2 : 3;
    else view += fromLight.z >= 0.0 ? 4 : 5;
  }
  // Normal offset of 1.5 texels at this distance against acne; the map holds back faces (seed 000 4.3.3).
  vec3 receiver = worldPosition + normal * (1.5 * shadow.localParams[view].x * length(fromLight));
  vec4 clip = shadow.localViewProjection[view] * vec4(receiver, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  vec4 rect = shadow.localAtlasRect[view];
  vec2 texel = shadow.localShadow.xy;
  vec2 uv = clamp(ndc.xy * 0.5 + 0.5, 1.5 * texel / rect.zw, 1.0 - 1.5 * texel / rect.zw);
  vec2 atlasUv = rect.xy + uv * rect.zw;
  float lit = 0.0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      lit += textureLod(localShadowAtlas, vec3(atlasUv + (vec2(x, y) - 0.5) * texel, ndc.z), 0.0);
  return lit * 0.25;
}

layout(location = 0) out vec4 diffuseLight;
layout(location = 1) out vec4 specularLight;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(deviceDepth, pixel, 0).r;
  if (isSkyDeviceDepth(frame.linearDepth, depth)) discard;  // sky: no surface to light

  // Listing 4.3, then the view position from the layer's (possibly off-axis) projection.
  uint layer = isFirstPersonDeviceDepth(frame.linearDepth, depth) ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
  float linearDepth = linearDepthFromDepthBuffer(frame.linearDepth, depth);
  vec2 ndc = gl_FragCoord.xy * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[layer].projection;
  vec3 viewPosition = vec3((ndc.x + p.z) * linearDepth / p.x, (ndc.y + p.w) * linearDepth / p.y, -linearDepth);
  mat4 worldFromView = frame.layers[layer].worldFromView;
  vec3 worldPosition = (worldFromView * vec4(viewPosition, 1.0)).xyz;
  vec3 toEye = normalize(worldFromView[3].xyz - worldPosition);

  vec4 normalAndGloss = texelFetch(normalGlossiness, pixel, 0);
  vec3 normal = normalize(normalAndGloss.xyz);
  float exponent = blinnPhongExponent(normalAndGloss.w);

  vec3 toLight;
  vec3 radiance;
  vec3 ambient = vec3(0.0);
  if (light.kind == S3D_LIGHT_AMBIENT_AND_SUN) {
    toLight = frame.directionToSun.xyz;
    radiance = frame.sunColor.rgb;
    if (light.shadowView >= 0) radiance *= texelFetch(sunShadowMask, pixel, 0).r;  // the deferred shadow mask
    // Hemisphere ambient (Y up), occluded by SSAO.
    ambient = frame.ambientColor.rgb * (normal.y * 0.7 + 0.3) * texelFetch(ambientOcclusion, pixel, 0).r;
  } else {
    vec3 offset = light.positionRadius.xyz - worldPosition;
    float distanceToLight = length(offset);
    toLight = offset / max(distanceToLight, 1e-6);
    radiance = light.color.rgb * pointLightFalloff(distanceToLight, light.positionRadius.w);
    if (light.kind == S3D_LIGHT_SPOT)
      radiance *= spotConeFalloff(dot(-toLight, light.spotDirection.xyz), light.spotCone.x, light.spotCone.y);
    if (light.shadowView >= 0 && dot(normal, toLight) > 0.0 && max(radiance.r, max(radiance.g, radiance.b)) > 0.0)
      radiance *= localShadow(worldPosition, normal);
  }
  float nDotL = max(dot(normal, toLight), 0.0);
  vec3 halfVector = normalize(toLight + toEye);
  diffuseLight = vec4(ambient + radiance * nDotL, 0.0);
  specularLight = vec4(radiance * (nDotL * normalizedBlinnPhong(dot(normal, halfVector), exponent)), 0.0);
}
