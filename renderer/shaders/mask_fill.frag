#version 450
// Masked render: before the G-buffer draws, every pixel outside the shade mask gets the nearest depth (the
// triangle's viewport puts it there), so the G-buffer's depth test rejects all its fragments before shading.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1, r32ui) uniform readonly uimage2D shadeMask;

void main() {
  ivec2 outputPixel = ivec2(gl_FragCoord.xy) / int(frame.options.x);
  if (imageLoad(shadeMask, outputPixel).r >= frame.tiles.z) discard;  // shaded: keeps the cleared far depth
}
