#version 450
// G-buffer pass under raster shading, cut-out objects: gbuffer.frag with the alpha test (gbuffer.glsl).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#define S3D_GBUFFER_CUTOUT
#include "gbuffer.glsl"
