#version 450
// The gather pass with a short tap array (the seed, searches of up to four taps) and the hybrid's base depth.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_BASE_DEPTH_OUTPUT
#include "stereo_gather.glsl"
