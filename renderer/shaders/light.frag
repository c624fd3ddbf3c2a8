#version 450
// Light accumulation (section 4.3.3): HDR diffuse and specular light per pixel, additive per light.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform sampler2D normalGlossiness;
layout(binding = 3) uniform sampler2D ambientOcclusion;  // 1 everywhere when SSAO is off
layout(push_constant) uniform Push { LightConstants light; };

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
    // Hemisphere ambient (Y up), occluded by SSAO.
    ambient = frame.ambientColor.rgb * (normal.y * 0.7 + 0.3) * texelFetch(ambientOcclusion, pixel, 0).r;
  } else {
    vec3 offset = light.positionRadius.xyz - worldPosition;
    float distanceToLight = length(offset);
    toLight = offset / max(distanceToLight, 1e-6);
    radiance = light.color.rgb * pointLightFalloff(distanceToLight, light.positionRadius.w);
  }
  float nDotL = max(dot(normal, toLight), 0.0);
  vec3 halfVector = normalize(toLight + toEye);
  diffuseLight = vec4(ambient + radiance * nDotL, 0.0);
  specularLight = vec4(radiance * (nDotL * normalizedBlinnPhong(dot(normal, halfVector), exponent)), 0.0);
}
