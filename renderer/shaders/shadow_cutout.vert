#version 450
// Shadow maps of cut-out casters: depth seen from the light, and where the caster samples its base-colour
// texture for the alpha test (shadow_cutout.frag).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(location = 0) in vec3 position;
layout(location = 1) in vec2 texCoord;
// uvRows, uvOffset: the base-colour texture transform (ObjectConstants' packing); alphaCutoff: x the material's
// coverage alpha, y the cutoff.
layout(push_constant) uniform Push { mat4 objectToClip; vec4 uvRows; vec2 uvOffset; vec2 alphaCutoff; };
layout(location = 0) out vec2 baseColorTexCoord;

void main() {
  gl_Position = objectToClip * vec4(position, 1.0);
  baseColorTexCoord = transformTexCoord(uvRows, uvOffset, texCoord);
}
