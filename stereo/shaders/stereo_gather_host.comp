#version 450
// The seed gather (and searches of up to four taps) straight from a host's sampled colour and depth buffer,
// into 8-bit display eyes: no input conversion pass.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_HOST_INPUTS
#include "stereo_gather.glsl"
