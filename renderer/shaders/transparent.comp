#version 450
// Transparent pass, compute implementation (GPUs; transparent.frag serves CPU devices): one dispatch per
// transparent object, farthest first, composites its triangles over the lit HDR image in the order a blended
// raster draw would (primitive order) and accumulates the transparent coverage (the error metrics' mask). On a GPU
// whose raster side is a small part of the chip a blended raster pass costs the bytes each fragment reads and
// writes; here each pixel reads and writes the HDR image once per object. No depth is written (the seed's
// transparency case: the stereo pass sees the surface behind).
//
// One workgroup per render tile of the object's screen rectangle: its threads set up a chunk of triangles
// (clip positions from the same transforms as geometry.vert, the tile's bounding-box test), then every pixel
// walks the chunk's overlapping triangles in order: perspective-correct barycentrics at the pixel centre
// (solved in clip space, as the G-buffer resolve does), inside test, clip-space depth range, the depth test
// against the opaque depth (no depth write), shading, "over" blending in registers.
#extension GL_GOOGLE_include_directive : require
#include "s3d/renderer/renderer_shared.h"
#include "material.glsl"

#define CHUNK (S3D_TILE_SIZE * S3D_TILE_SIZE)
layout(local_size_x = S3D_TILE_SIZE, local_size_y = S3D_TILE_SIZE) in;
layout(binding = 0) uniform Frame { FrameConstants frame; };
layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(std430, binding = 2) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 3) readonly buffer Vertices { float vertexFloats[]; };    // Vertex: position, normal
#define S3D_SURFACE_VERTICES_BINDING 4
#include "surface_vertices.glsl"
layout(binding = 5) uniform sampler2D deviceDepth;
layout(binding = 6, rgba16f) uniform image2D hdrColor;
layout(binding = 7, rgba8) uniform image2D coverage;  // red: 1 - prod(1 - opacity) of the layers over the pixel
layout(binding = 8) uniform sampler2D baseColor;  // sRGB format: read as linear; white 1x1 when untextured
layout(binding = 9) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(binding = 10, r32ui) uniform readonly uimage2D shadeMask;  // output size; read only when pass.masked
layout(push_constant) uniform Push { TransparentConstants pass; };

shared vec4 clip0[CHUNK], clip1[CHUNK], clip2[CHUNK];
shared uint overlapsTile[CHUNK];

vec3 vertexPosition(uint v) { return vec3(vertexFloats[6u * v], vertexFloats[6u * v + 1u], vertexFloats[6u * v + 2u]); }
vec3 vertexNormal(uint v) { return vec3(vertexFloats[6u * v + 3u], vertexFloats[6u * v + 4u], vertexFloats[6u * v + 5u]); }
uvec3 triangleVertices(uint triangle) {
  uint first = objects[pass.objectIndex].firstIndex + 3u * triangle;
  return uvec3(indices[first], indices[first + 1u], indices[first + 2u]) + objects[pass.objectIndex].vertexOffset;
}

// Whether the triangle's screen bounding box reaches a pixel centre of the tile (any vertex at or behind the
// eye plane: assumed to, its projection being unbounded).
bool overlaps(vec4 c0, vec4 c1, vec4 c2, vec2 tileFirstCentre, vec2 tileLastCentre) {
  if (c0.w <= 0.0 || c1.w <= 0.0 || c2.w <= 0.0) return true;
  vec2 s0 = (c0.xy / c0.w * 0.5 + 0.5) * frame.screen.xy, s1 = (c1.xy / c1.w * 0.5 + 0.5) * frame.screen.xy;
  vec2 s2 = (c2.xy / c2.w * 0.5 + 0.5) * frame.screen.xy;
  vec2 lo = min(s0, min(s1, s2)) - 1.0, hi = max(s0, max(s1, s2)) + 1.0;  // a pixel of slack for rounding
  return all(lessThanEqual(lo, tileLastCentre)) && all(greaterThanEqual(hi, tileFirstCentre));
}

#include "transparent.glsl"

// The triangle's surface at barycentrics b, interpolated as the raster implementation's varyings are, shaded.
vec4 shade(uvec3 v, vec3 b) {
  ObjectConstants object = objects[pass.objectIndex];
  vec3 localPosition = b.x * vertexPosition(v.x) + b.y * vertexPosition(v.y) + b.z * vertexPosition(v.z);
  vec3 localNormal = b.x * vertexNormal(v.x) + b.y * vertexNormal(v.y) + b.z * vertexNormal(v.z);
  vec2 texCoord = b.x * vertexTexCoord(v.x) + b.y * vertexTexCoord(v.y) + b.z * vertexTexCoord(v.z);
  vec4 localTangent = b.x * vertexTangent(v.x) + b.y * vertexTangent(v.y) + b.z * vertexTangent(v.z);
  vec3 worldPosition = (object.objectToWorld * vec4(localPosition, 1.0)).xyz;
  vec3 worldNormal = mat3(object.normalToWorld) * localNormal;
  vec4 worldTangent = vec4(mat3(object.objectToWorld) * localTangent.xyz, localTangent.w);
  return shadeTransparent(object, worldPosition, worldNormal, worldTangent, texCoord, baseColor, normalMap);
}

void main() {
  // The coverage-initializing dispatch runs over every tile; those outside the object's rectangle only clear.
  uvec2 tile = (pass.initializesCoverage != 0u ? uvec2(0u) : pass.tileRect.xy) + gl_WorkGroupID.xy;
  ivec2 pixel = ivec2(tile * S3D_TILE_SIZE + gl_LocalInvocationID.xy);
  bool onScreen = all(lessThan(pixel, ivec2(frame.screen.xy)));
  // A masked render composites only the shaded pixels: the rest of the image is not lit and not used.
  bool shaded = onScreen && (pass.masked == 0u || imageLoad(shadeMask, pixel / int(frame.options.x)).r >= frame.tiles.z);
  bool inRect = all(greaterThanEqual(tile, pass.tileRect.xy)) && all(lessThan(tile, pass.tileRect.zw));
  vec2 ndc = (vec2(pixel) + 0.5) * frame.screen.zw * 2.0 - 1.0;
  float opaqueDepth = onScreen && inRect ? texelFetch(deviceDepth, pixel, 0).r : 0.0;
  vec2 tileFirstCentre = vec2(tile * S3D_TILE_SIZE) + 0.5;
  vec2 tileLastCentre = tileFirstCentre + float(S3D_TILE_SIZE - 1);
  mat4 objectToClip = frame.layers[objects[pass.objectIndex].layer].viewProjection * objects[pass.objectIndex].objectToLayer;
  uint local = gl_LocalInvocationIndex;

  bool covered = false;
  vec3 color = vec3(0.0);
  float keptAlpha = 0.0;  // the opaque pass's alpha: blending keeps it
  float transmitted = 1.0;  // prod(1 - opacity) of this object's layers over the pixel
  for (uint chunk = 0u; inRect && chunk < pass.triangleCount; chunk += CHUNK) {
    uint triangle = chunk + local;
    bool tileOverlap = false;
    if (triangle < pass.triangleCount) {
      uvec3 v = triangleVertices(triangle);
      // precise: the same clip positions as geometry.vert computes.
      precise vec4 c0 = objectToClip * vec4(vertexPosition(v.x), 1.0);
      precise vec4 c1 = objectToClip * vec4(vertexPosition(v.y), 1.0);
      precise vec4 c2 = objectToClip * vec4(vertexPosition(v.z), 1.0);
      clip0[local] = c0;
      clip1[local] = c1;
      clip2[local] = c2;
      tileOverlap = overlaps(c0, c1, c2, tileFirstCentre, tileLastCentre);
    }
    overlapsTile[local] = tileOverlap ? 1u : 0u;
    barrier();
    uint count = min(uint(CHUNK), pass.triangleCount - chunk);
    for (uint i = 0u; shaded && i < count; ++i) {
      if (overlapsTile[i] == 0u) continue;
      vec4 c0 = clip0[i], c1 = clip1[i], c2 = clip2[i];
      // The surface point b0 c0 + b1 c1 + b2 c2 (b summing to 1) that projects to the pixel centre.
      vec3 ex = vec3(c0.x, c1.x, c2.x) - ndc.x * vec3(c0.w, c1.w, c2.w);
      vec3 ey = vec3(c0.y, c1.y, c2.y) - ndc.y * vec3(c0.w, c1.w, c2.w);
      vec3 b = cross(ex, ey);
      float sum = b.x + b.y + b.z;
      if (sum == 0.0) continue;  // seen edge-on: no fragments
      b /= sum;
      if (any(lessThan(b, vec3(0.0)))) continue;  // outside
      vec4 point = b.x * c0 + b.y * c1 + b.z * c2;
      if (point.w <= 0.0 || point.z < 0.0 || point.z > point.w) continue;  // behind the eye or clipped in depth
      float fragmentDepth = mix(pass.depthRange.x, pass.depthRange.y, point.z / point.w);
      if (pass.reversedZ != 0u ? fragmentDepth <= opaqueDepth : fragmentDepth >= opaqueDepth) continue;
      if (!covered) {
        vec4 lit = imageLoad(hdrColor, pixel);
        color = lit.rgb;
        keptAlpha = lit.a;
        covered = true;
      }
      vec4 fragment = shade(triangleVertices(chunk + i), b);
      color = fragment.rgb * fragment.a + color * (1.0 - fragment.a);
      transmitted *= 1.0 - fragment.a;
    }
    barrier();
  }
  if (!onScreen) return;
  if (covered) imageStore(hdrColor, pixel, vec4(color, keptAlpha));
  if (pass.initializesCoverage != 0u) {
    imageStore(coverage, pixel, vec4(vec3(1.0 - transmitted), 0.0));
  } else if (covered) {
    float before = imageLoad(coverage, pixel).r;
    imageStore(coverage, pixel, vec4(vec3(1.0 - (1.0 - before) * transmitted), 0.0));
  }
}
