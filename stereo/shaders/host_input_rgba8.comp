#version 450
// Host input conversion into the 8-bit display colour of the stereo kernel.
#extension GL_GOOGLE_include_directive : require
#define S3D_HOST_COLOR_FORMAT rgba8
#include "host_input.glsl"
