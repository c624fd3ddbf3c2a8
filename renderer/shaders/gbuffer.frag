#version 450
// G-buffer: world normal (normal-mapped where the object has a normal map) and glossiness (depth comes from
// the depth attachment).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 3) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 2) in vec2 texCoord;
layout(location = 3) in vec4 worldTangent;
layout(location = 0) out vec4 normalGlossiness;

void main() {
  ObjectConstants object = objects[objectIndex];
  vec3 normal = shadingNormal(worldNormal, worldTangent, texCoord, object.normalScale, normalMap);
  normalGlossiness = vec4(normal, object.specular.a);
}
