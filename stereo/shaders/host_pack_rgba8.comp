#version 450
// Output packing of 8-bit display eyes.
#extension GL_GOOGLE_include_directive : require
#define S3D_HOST_COLOR_FORMAT rgba8
#include "host_pack.glsl"
