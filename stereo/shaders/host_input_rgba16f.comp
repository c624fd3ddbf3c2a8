#version 450
// Host input conversion into half-float colour (HDR input, gathered without clipping).
#extension GL_GOOGLE_include_directive : require
#define S3D_HOST_COLOR_FORMAT rgba16f
#include "host_input.glsl"
