#version 450
// G-buffer resolve: per render pixel, the surface its visibility id names (object, triangle), evaluated at the
// pixel centre as the raster pass's interpolation would: the triangle's clip positions from the same
// transforms as geometry.vert, perspective-correct barycentrics (solved in clip space, so vertices behind the
// eye need no care), the interpolated world normal; written as the textured path writes it (normal and
// glossiness, packMaterial). Sky pixels (cleared depth) get the cleared values; pixels the raster pass shaded
// itself (S3D_RASTER_SHADED) are kept. A masked render resolves the shade-mask pixels of the listed tiles.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"

layout(local_size_x = S3D_TILE_SIZE, local_size_y = S3D_TILE_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(binding = 1) uniform sampler2D deviceDepth;
layout(binding = 2) uniform usampler2D visibility;
layout(std430, binding = 3) readonly buffer Objects { ObjectConstants objects[]; };
layout(std430, binding = 4) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 5) readonly buffer Vertices { float vertexFloats[]; };  // Vertex: position, normal
layout(binding = 6, rgba16f) uniform writeonly image2D normalGlossiness;
layout(binding = 7, rg32ui) uniform writeonly uimage2D material;
#define S3D_TILES_BINDING 8
#define S3D_SHADE_MASK_BINDING 9
#include "tiles.glsl"

vec3 vertexPosition(uint v) { return vec3(vertexFloats[6u * v], vertexFloats[6u * v + 1u], vertexFloats[6u * v + 2u]); }
vec3 vertexNormal(uint v) { return vec3(vertexFloats[6u * v + 3u], vertexFloats[6u * v + 4u], vertexFloats[6u * v + 5u]); }

void main() {
  ivec2 pixel = maskedTile() * S3D_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.screen.xy))) || !shadeMasked(pixel)) return;
  if (isSkyDeviceDepth(frame.linearDepth, texelFetch(deviceDepth, pixel, 0).r)) {
    imageStore(normalGlossiness, pixel, vec4(0.0));
    imageStore(material, pixel, uvec4(0u, S3D_NO_OBJECT << 16, 0u, 0u));
    return;
  }
  countShaded(S3D_COUNT_GBUFFER, 1u);
  uvec2 id = texelFetch(visibility, pixel, 0).rg;
  if (id.x == S3D_RASTER_SHADED) return;
  // The object's fields one by one: a copy of the whole struct would load all of it.
  uint objectIndex = unpackVisibilityObject(id, frame.options);
  uint first = objects[objectIndex].firstIndex + 3u * unpackVisibilityTriangle(id, frame.options);
  uvec3 v = uvec3(indices[first], indices[first + 1u], indices[first + 2u]) + objects[objectIndex].vertexOffset;
  mat4 objectToClip = frame.layers[objects[objectIndex].layer].viewProjection * objects[objectIndex].objectToLayer;
  vec4 c0 = objectToClip * vec4(vertexPosition(v.x), 1.0);
  vec4 c1 = objectToClip * vec4(vertexPosition(v.y), 1.0);
  vec4 c2 = objectToClip * vec4(vertexPosition(v.z), 1.0);
  // The surface point b0 c0 + b1 c1 + b2 c2 (b summing to 1) projects to the pixel centre's ndc: two linear
  // equations in b whose solution is the cross product of their coefficient vectors, normalized.
  vec2 ndc = (vec2(pixel) + 0.5) * frame.screen.zw * 2.0 - 1.0;
  vec3 ex = vec3(c0.x, c1.x, c2.x) - ndc.x * vec3(c0.w, c1.w, c2.w);
  vec3 ey = vec3(c0.y, c1.y, c2.y) - ndc.y * vec3(c0.w, c1.w, c2.w);
  vec3 b = cross(ex, ey);
  float sum = b.x + b.y + b.z;
  b = sum != 0.0 ? b / sum : vec3(1.0 / 3.0);  // a triangle seen edge-on: its centroid
  vec3 normal = b.x * vertexNormal(v.x) + b.y * vertexNormal(v.y) + b.z * vertexNormal(v.z);
  imageStore(normalGlossiness, pixel,
             vec4(normalize(mat3(objects[objectIndex].normalToWorld) * normal), objects[objectIndex].specular.a));
  imageStore(material, pixel, uvec4(packMaterial(objects[objectIndex].albedo.rgb, objectIndex), 0u, 0u));
}
