#version 450
// Output packing of half-float (HDR) eyes.
#extension GL_GOOGLE_include_directive : require
#define S3D_HOST_COLOR_FORMAT rgba16f
#include "host_pack.glsl"
