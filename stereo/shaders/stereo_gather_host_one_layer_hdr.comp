#version 450
// stereo_gather_host_one_layer.comp for a host's HDR colour (RGBA16F, B10G11R11): half-float eyes.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_HOST_INPUTS
#define S3D_STEREO_HOST_ONE_LAYER_DEPTH
#define S3D_STEREO_COLOR_FORMAT rgba16f
#include "stereo_gather.glsl"
