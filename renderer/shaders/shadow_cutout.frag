#version 450
// Shadow maps of cut-out casters: a fragment the G-buffer's alpha test drops casts no shadow either.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform sampler2D baseColor;  // white 1x1 when untextured
layout(push_constant) uniform Push { mat4 objectToClip; vec4 uvRows; vec2 uvOffset; vec2 alphaCutoff; };
layout(location = 0) in vec2 baseColorTexCoord;

void main() {
  if (cutOut(alphaCutoff.x, textureLod(baseColor, baseColorTexCoord, 0.0).a, alphaCutoff.y)) discard;
}
