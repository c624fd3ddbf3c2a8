#version 450
// G-buffer pass under visibility shading, the untextured objects of a scene with textured ones: the ids after
// the normal and material targets those write (visibility.glsl).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#define S3D_VISIBILITY_BESIDE_SURFACE_TARGETS
#include "visibility.glsl"
