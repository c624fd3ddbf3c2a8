#version 450
// Transparent pass: alpha-blended surfaces after opaque shading, forward-lit by hemisphere ambient and the
// sun (point lights are left out: they live in the deferred light buffers). They write no depth, which is
// the case the seed says image displacement gets wrong: the stereo pass sees the surface behind them.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 2) uniform sampler2D baseColor;  // sRGB format: read as linear; white 1x1 when untextured
layout(binding = 3) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 2) in vec2 texCoord;
layout(location = 3) in vec4 worldTangent;
layout(location = 0) out vec4 hdrColor;
layout(location = 1) out vec4 coverage;  // alpha-blended 1: the transparent region of the error metrics

void main() {
  ObjectConstants object = objects[objectIndex];
  vec3 toEye = normalize(frame.layers[object.layer].worldFromView[3].xyz - worldPosition);
  vec3 normal = shadingNormal(worldNormal, worldTangent, texCoord, object.normalScale, normalMap);
  if (dot(normal, toEye) < 0.0) normal = -normal;  // panes are seen from both sides
  vec3 toSun = frame.directionToSun.xyz;
  float nDotL = max(dot(normal, toSun), 0.0);
  vec3 diffuse = frame.ambientColor.rgb * (normal.y * 0.7 + 0.3) + frame.sunColor.rgb * nDotL;
  float exponent = blinnPhongExponent(object.specular.a);
  vec3 specular = frame.sunColor.rgb * (nDotL * normalizedBlinnPhong(dot(normal, normalize(toSun + toEye)), exponent));
  float nDotV = clamp(dot(normal, toEye), 0.0, 1.0);
  vec3 fresnel = object.specular.rgb + (1.0 - object.specular.rgb) * pow(1.0 - nDotV, 5.0);  // Schlick
  // Specular is not dimmed by the opacity: glass reflects even where it lets most light through.
  vec4 albedo = object.albedo * textureLod(baseColor, texCoord, 0.0);  // texture alpha scales the opacity
  hdrColor = vec4(albedo.rgb * diffuse + fresnel * specular / max(albedo.a, 1e-3), albedo.a);
  coverage = vec4(1.0, 1.0, 1.0, albedo.a);
}
