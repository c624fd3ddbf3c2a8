#version 450
// Transparent pass, raster implementation (CPU devices; transparent.comp serves GPUs): alpha-blended surfaces
// after opaque shading, drawn back to front, depth-tested against the opaque depth. They write no depth, which is
// the case the seed says image displacement gets wrong: the stereo pass sees the surface behind them.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 2) uniform sampler2D baseColor;  // sRGB format: read as linear; white 1x1 when untextured
layout(binding = 3) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(push_constant) uniform Push { uint objectIndex; };

#include "transparent.glsl"

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 2) in vec2 texCoord;
layout(location = 3) in vec4 worldTangent;
layout(location = 0) out vec4 hdrColor;
layout(location = 1) out vec4 coverage;  // alpha-blended 1: the transparent region of the error metrics

void main() {
  hdrColor = shadeTransparent(objects[objectIndex], worldPosition, worldNormal, worldTangent, texCoord, baseColor, normalMap);
  coverage = vec4(1.0, 1.0, 1.0, hdrColor.a);
}
