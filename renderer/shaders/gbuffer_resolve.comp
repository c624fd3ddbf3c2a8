#version 450
// G-buffer resolve: per render pixel, the surface its visibility id names (object, triangle), evaluated at the
// pixel centre as the raster pass's interpolation would: the triangle's clip positions from the same
// transforms as geometry.vert, perspective-correct barycentrics (solved in clip space, so vertices behind the
// eye need no care), the interpolated world normal; written as the textured path writes it (normal and
// glossiness, packMaterial). Sky pixels (cleared depth) get the cleared values; pixels the raster pass shaded
// itself (S3D_RASTER_SHADED) are kept. A masked render resolves the shade-mask pixels of the listed tiles.
// With kSurfaceMaterials (ray-cast surfaces, where no raster pass shades textured or double-sided objects) it
// also applies what gbuffer.glsl does for them: the base-colour texture, the normal map, and a double-sided
// object's back face seen with its normal flipped.
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
#define S3D_SURFACE_VERTICES_BINDING 10
#include "surface_vertices.glsl"
#define S3D_TEXTURE_TABLE_BINDING 11
#define S3D_TEXELS_BINDING 12
#include "material.glsl"
#include "surface_texels.glsl"
layout(constant_id = 2) const bool kSurfaceMaterials = false;

vec3 vertexPosition(uint v) { return vec3(vertexFloats[6u * v], vertexFloats[6u * v + 1u], vertexFloats[6u * v + 2u]); }
vec3 vertexNormal(uint v) { return vec3(vertexFloats[6u * v + 3u], vertexFloats[6u * v + 4u], vertexFloats[6u * v + 5u]); }

// A textured or double-sided object's normal/glossiness and material at barycentrics b, as gbuffer.glsl writes
// them. Facing: the sign of the triangle's homogeneous (x, y, w) determinant, negative for a counter-clockwise
// (front) face on screen, as the raster pass's front face and the ray cast's culling define it.
void writeSurfaceMaterial(ivec2 pixel, uint objectIndex, uvec3 v, vec3 b, vec3 normal, vec4 c0, vec4 c1, vec4 c2) {
  uvec4 textures = objects[objectIndex].surfaceTextures;
  bool backFace = textures.z != 0u && determinant(mat3(c0.xyw, c1.xyw, c2.xyw)) > 0.0;
  vec3 worldNormal = mat3(objects[objectIndex].normalToWorld) * (backFace ? -normal : normal);
  vec2 texCoord = b.x * vertexTexCoord(v.x) + b.y * vertexTexCoord(v.y) + b.z * vertexTexCoord(v.z);
  vec4 uvOffsets = objects[objectIndex].uvOffsets;
  vec4 texel = textures.x == S3D_NO_TEXTURE
                   ? vec4(1.0)
                   : sampleTexels(textures.x, transformTexCoord(objects[objectIndex].baseColorUv, uvOffsets.xy, texCoord));
  vec3 shading = normalize(worldNormal);
  if (textures.y != S3D_NO_TEXTURE) {
    vec4 tangent = b.x * vertexTangent(v.x) + b.y * vertexTangent(v.y) + b.z * vertexTangent(v.z);
    vec4 worldTangent = vec4(mat3(objects[objectIndex].objectToWorld) * tangent.xyz, tangent.w);
    vec2 normalUv = transformTexCoord(objects[objectIndex].normalUv, uvOffsets.zw, texCoord);
    shading = shadingNormalFromTexel(worldNormal, worldTangent, sampleTexels(textures.y, normalUv).xyz,
                                     objects[objectIndex].normalScale);
  }
  imageStore(normalGlossiness, pixel, vec4(shading, objects[objectIndex].specular.a));
  imageStore(material, pixel, uvec4(packMaterial(objects[objectIndex].albedo.rgb * texel.rgb, objectIndex), 0u, 0u));
}

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
  if (kSurfaceMaterials && objects[objectIndex].surfaceTextures != uvec4(S3D_NO_TEXTURE, S3D_NO_TEXTURE, 0u, 0u)) {
    writeSurfaceMaterial(pixel, objectIndex, v, b, normal, c0, c1, c2);
    return;
  }
  imageStore(normalGlossiness, pixel,
             vec4(normalize(mat3(objects[objectIndex].normalToWorld) * normal), objects[objectIndex].specular.a));
  imageStore(material, pixel, uvec4(packMaterial(objects[objectIndex].albedo.rgb, objectIndex), 0u, 0u));
}
