#version 450
// G-buffer pass under raster shading: every object writes normal/glossiness and material (gbuffer.glsl).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "gbuffer.glsl"
