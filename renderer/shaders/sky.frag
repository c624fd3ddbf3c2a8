#version 450
// Sky at infinite distance: its color depends on the view direction only.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(location = 0) out vec4 hdrColor;

void main() {
  vec2 ndc = gl_FragCoord.xy * frame.screen.zw * 2.0 - 1.0;
  vec4 p = frame.layers[S3D_LAYER_WORLD].projection;
  vec3 viewDirection = vec3((ndc.x + p.z) / p.x, (ndc.y + p.w) / p.y, -1.0);
  vec3 direction = normalize(mat3(frame.layers[S3D_LAYER_WORLD].worldFromView) * viewDirection);
  vec3 color = direction.y >= 0.0 ? mix(frame.skyHorizon.rgb, frame.skyZenith.rgb, sqrt(direction.y))
                                   : mix(frame.skyHorizon.rgb, frame.skyGround.rgb, sqrt(-direction.y));
  hdrColor = vec4(color, 1.0);
}
