#version 450
// stereo_gather_host.comp for a device depth buffer of one layer (no first-person depth range): the taps'
// minimum in device depth, converted once per side. Its own module, so the per-tap conversion's registers do not
// weigh on it.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_HOST_INPUTS
#define S3D_STEREO_HOST_ONE_LAYER_DEPTH
#include "stereo_gather.glsl"
