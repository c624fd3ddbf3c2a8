// The renderer's second vertex stream (gpu::SurfaceVertex: texture coordinates, tangent; zeros for meshes without
// it) as tightly packed floats, for the shaders that pull vertices themselves. Define
// S3D_SURFACE_VERTICES_BINDING first.
layout(std430, binding = S3D_SURFACE_VERTICES_BINDING) readonly buffer Surfaces { float surfaceFloats[]; };

vec2 vertexTexCoord(uint v) { return vec2(surfaceFloats[6u * v], surfaceFloats[6u * v + 1u]); }
vec4 vertexTangent(uint v) {
  return vec4(surfaceFloats[6u * v + 2u], surfaceFloats[6u * v + 3u], surfaceFloats[6u * v + 4u], surfaceFloats[6u * v + 5u]);
}
