#version 450
// Forward method, row kernel (stereo_forward_row.glsl): the eyes only, the z-buffers stay in shared memory.
#extension GL_GOOGLE_include_directive : require
#include "stereo_forward_row.glsl"
