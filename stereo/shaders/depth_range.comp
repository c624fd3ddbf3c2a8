#version 450
// The frame's depth range (depth_range.h) of a linear depth image (R32F storage image).
#extension GL_GOOGLE_include_directive : require

layout(binding = 0, r32f) uniform readonly image2D linearDepth;
#define S3D_DEPTH_AT(texel) imageLoad(linearDepth, texel).r
#define S3D_DEPTH_SIZE() imageSize(linearDepth)
#include "depth_range.glsl"
