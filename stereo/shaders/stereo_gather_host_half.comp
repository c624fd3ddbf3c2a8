#version 450
// stereo_gather_host.comp for the half packings (side-by-side, top-bottom) into one 8-bit target: each packed
// pixel gathers the eye pixels its box filter covers. A module of its own, so the filter's registers do not cost
// the other outputs' gather.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_HOST_INPUTS
#define S3D_STEREO_HOST_HALF_PACKING
#include "stereo_gather.glsl"
