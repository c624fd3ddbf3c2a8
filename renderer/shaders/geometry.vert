#version 450
// Shared by the G-buffer, the depth-only pass of a masked render and the transparent raster pass: one module
// gives them the same depth (transparent.comp repeats its transforms). Vertices are pulled from storage buffers
// (non-indexed draws of the mesh's index range), so each triangle knows its index within the mesh: the
// G-buffer's visibility id.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(std430, binding = 4) readonly buffer Indices { uint indices[]; };
// Vertex (position, normal) and gpu::SurfaceVertex (texture coordinates, tangent), tightly packed floats.
layout(std430, binding = 5) readonly buffer Vertices { float vertexFloats[]; };
layout(std430, binding = 6) readonly buffer Surfaces { float surfaceFloats[]; };
layout(push_constant) uniform Push { uint objectIndex; };

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec3 worldPosition;
layout(location = 2) out vec2 surfaceTexCoord;
layout(location = 3) out vec4 worldTangent;
layout(location = 4) flat out uvec2 visibility;

void main() {
  ObjectConstants object = objects[objectIndex];
  // The draw's first vertex is the mesh's first index: gl_VertexIndex walks the mesh's index range.
  uint v = indices[gl_VertexIndex] + object.vertexOffset;
  vec3 position = vec3(vertexFloats[6u * v], vertexFloats[6u * v + 1u], vertexFloats[6u * v + 2u]);
  vec3 normal = vec3(vertexFloats[6u * v + 3u], vertexFloats[6u * v + 4u], vertexFloats[6u * v + 5u]);
  vec2 texCoord = vec2(surfaceFloats[6u * v], surfaceFloats[6u * v + 1u]);
  vec4 tangent = vec4(surfaceFloats[6u * v + 2u], surfaceFloats[6u * v + 3u], surfaceFloats[6u * v + 4u],
                      surfaceFloats[6u * v + 5u]);
  // precise: no contraction differences, so every pipeline computes the same depth from this same module.
  precise vec4 clipPosition = frame.layers[object.layer].viewProjection * (object.objectToLayer * vec4(position, 1.0));
  gl_Position = clipPosition;
  worldNormal = mat3(object.normalToWorld) * normal;
  worldPosition = (object.objectToWorld * vec4(position, 1.0)).xyz;
  surfaceTexCoord = texCoord;
  worldTangent = vec4(mat3(object.objectToWorld) * tangent.xyz, tangent.w);  // tangents follow the surface
  visibility = packVisibility(objectIndex, uint(gl_VertexIndex - object.firstIndex) / 3u, frame.options);
}
