#version 450
// stereo_search.comp on row tiles: the N-tap depth search from shared memory.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_MAX_TAPS
#include "stereo_gather_tiled.glsl"
