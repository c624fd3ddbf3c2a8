#version 450
// The N-tap search gather on half-float colour (a host's HDR input, before tone mapping).
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_MAX_TAPS
#define S3D_STEREO_COLOR_FORMAT rgba16f
#include "stereo_gather.glsl"
