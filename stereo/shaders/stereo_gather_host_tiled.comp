#version 450
// stereo_gather_host.comp on row tiles: the host's 8-bit colour and depth converted once per texel of the tile
// (a separation's worth of margin each side) instead of at every tap and filter fetch.
#extension GL_GOOGLE_include_directive : require
#define S3D_STEREO_TAP_CAPACITY S3D_STEREO_SMALL_TAP_CAPACITY
#define S3D_STEREO_HOST_INPUTS
#include "stereo_gather_tiled.glsl"
