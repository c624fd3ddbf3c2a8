#version 450
// G-buffer pass under visibility shading, textured objects: normal/glossiness and material (gbuffer.glsl) and
// S3D_RASTER_SHADED as the visibility id, so the G-buffer resolve keeps them.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#define S3D_GBUFFER_MARKS_VISIBILITY
#include "gbuffer.glsl"
