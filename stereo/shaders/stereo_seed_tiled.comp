#version 450
// stereo_seed.comp on row tiles: Listing 4.5's three taps (and searches of up to four) from shared memory.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#include "stereo_gather_tiled.glsl"
