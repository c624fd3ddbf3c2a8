#version 450
// Shared by the G-buffer, the depth-only pass of a masked render and the transparent pass: one module gives them
// the same depth.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 texCoord;  // second stream: SurfaceVertex
layout(location = 3) in vec4 tangent;

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec3 worldPosition;
layout(location = 2) out vec2 surfaceTexCoord;
layout(location = 3) out vec4 worldTangent;

void main() {
  ObjectConstants object = objects[objectIndex];
  // precise: no contraction differences, so both pipelines compute the same depth from this same module.
  precise vec4 clipPosition = frame.layers[object.layer].viewProjection * (object.objectToLayer * vec4(position, 1.0));
  gl_Position = clipPosition;
  worldNormal = mat3(object.normalToWorld) * normal;
  worldPosition = (object.objectToWorld * vec4(position, 1.0)).xyz;
  surfaceTexCoord = texCoord;
  worldTangent = vec4(mat3(object.objectToWorld) * tangent.xyz, tangent.w);  // tangents follow the surface
}
