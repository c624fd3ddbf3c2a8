#version 450
// G-buffer: world normal and glossiness (depth comes from the depth attachment).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 0) out vec4 normalGlossiness;

void main() { normalGlossiness = vec4(normalize(worldNormal), objects[objectIndex].specular.a); }
