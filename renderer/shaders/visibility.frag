#version 450
// G-buffer pass under visibility shading, a scene without textured objects: the ids alone (visibility.glsl).
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "visibility.glsl"
