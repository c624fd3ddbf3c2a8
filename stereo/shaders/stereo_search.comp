#version 450
// The gather pass with the full tap array: the N-tap depth search.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_MAX_TAPS
#include "stereo_gather.glsl"
