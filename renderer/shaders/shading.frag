#version 450
// Shading pass: the geometry drawn again (depth EQUAL) applies albedo and Fresnel to the accumulated light.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 2) uniform sampler2D diffuseLight;
layout(binding = 3) uniform sampler2D specularLight;
layout(binding = 4) uniform sampler2D baseColor;  // sRGB format: read as linear; white 1x1 when untextured
layout(binding = 5) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 2) in vec2 texCoord;
layout(location = 3) in vec4 worldTangent;
layout(location = 0) out vec4 hdrColor;

void main() {
  ObjectConstants object = objects[objectIndex];
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec3 toEye = normalize(frame.layers[object.layer].worldFromView[3].xyz - worldPosition);
  vec3 normal = shadingNormal(worldNormal, worldTangent, texCoord, object.normalScale, normalMap);
  float nDotV = clamp(dot(normal, toEye), 0.0, 1.0);
  vec3 f0 = object.specular.rgb;
  vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - nDotV, 5.0);  // Schlick
  vec3 albedo = object.albedo.rgb * texture(baseColor, texCoord).rgb;
  vec3 color = albedo * texelFetch(diffuseLight, pixel, 0).rgb + fresnel * texelFetch(specularLight, pixel, 0).rgb;
  hdrColor = vec4(color, 1.0);
}
