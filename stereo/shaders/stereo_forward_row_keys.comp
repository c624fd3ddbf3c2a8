#version 450
// Forward method, row kernel (stereo_forward_row.glsl) that also stores both eyes' z-buffers in the key images.
#extension GL_GOOGLE_include_directive : require
#define S3D_FORWARD_ROW_WRITES_KEYS
#include "stereo_forward_row.glsl"
