#version 450
// Depth-only passes (a masked render's ambient-occlusion depth) for cut-out objects: the G-buffer's alpha test,
// so the depth matches the G-buffer's (geometry.vert gives the same positions).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 2) uniform sampler2D baseColor;  // white 1x1 when untextured
layout(push_constant) uniform Push { uint objectIndex; };
layout(location = 2) in vec2 texCoord;

void main() {
  ObjectConstants object = objects[objectIndex];
  float alpha = textureLod(baseColor, baseColorTexCoord(object, texCoord), 0.0).a;
  if (cutOut(object.albedo.a, alpha, object.emissive.a)) discard;
}
