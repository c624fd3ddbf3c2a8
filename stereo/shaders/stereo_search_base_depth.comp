#version 450
// The gather pass with the full tap array and the hybrid's base depth.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_MAX_TAPS
#define S3D_STEREO_BASE_DEPTH_OUTPUT
#include "stereo_gather.glsl"
