// The G-buffer pass's fragment shader where the raster pass shades the surface (gbuffer.frag: every object
// under raster shading; gbuffer_marked.frag: textured objects under visibility shading): world normal
// (normal-mapped where the object has a normal map) and glossiness; the material the lighting pass applies:
// albedo with its base-color texture and the object's index (its F0), packMaterial. Marked (with
// S3D_GBUFFER_MARKS_VISIBILITY defined): also S3D_RASTER_SHADED as the visibility id, so the G-buffer resolve
// keeps what it wrote. Depth comes from the depth attachment. Cut-out objects (gbuffer_cutout.frag,
// gbuffer_marked_cutout.frag: S3D_GBUFFER_CUTOUT defined) discard the fragments their alpha test drops, which
// keeps those pipelines alone from testing depth before shading. Include after the #version and
// renderer_shared.h.
#include "material.glsl"

#ifndef S3D_GBUFFER_CUTOUT
// No discard or depth write here, so the depth test runs before shading (a masked render relies on it).
layout(early_fragment_tests) in;
#endif

layout(std430, binding = 1) readonly buffer Objects { ObjectConstants objects[]; };
layout(binding = 2) uniform sampler2D baseColor;  // sRGB format: read as linear; white 1x1 when untextured
layout(binding = 3) uniform sampler2D normalMap;  // flat 1x1 when the object has none
layout(push_constant) uniform Push { uint objectIndex; };
// Whether the object has a base-color texture and a normal map: one pipeline per combination, so an object
// does no texture work it does not need (a CPU rasterizer would run a skipped branch anyway).
layout(constant_id = 0) const bool kBaseColorTexture = true;
layout(constant_id = 1) const bool kNormalMap = true;
// Double-sided objects (drawn unculled): back faces are shaded with the normal flipped toward the viewer.
layout(constant_id = 2) const bool kDoubleSided = false;

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 worldPosition;
layout(location = 2) in vec2 texCoord;
layout(location = 3) in vec4 worldTangent;
layout(location = 0) out vec4 normalGlossiness;
layout(location = 1) out uvec2 material;
#ifdef S3D_GBUFFER_MARKS_VISIBILITY
layout(location = 2) out uvec2 visibilityId;
#endif

void main() {
  ObjectConstants object = objects[objectIndex];
  // Level 0 explicitly: the textures have one level, and no derivatives are needed for it.
  vec4 texel = kBaseColorTexture ? textureLod(baseColor, baseColorTexCoord(object, texCoord), 0.0) : vec4(1.0);
#ifdef S3D_GBUFFER_CUTOUT
  if (cutOut(object.albedo.a, texel.a, object.emissive.a)) discard;
#endif
#ifdef S3D_GBUFFER_MARKS_VISIBILITY
  visibilityId = uvec2(S3D_RASTER_SHADED);
#endif
  vec3 facingNormal = kDoubleSided && !gl_FrontFacing ? -worldNormal : worldNormal;
  vec3 normal = kNormalMap ? shadingNormal(facingNormal, worldTangent, normalMapTexCoord(object, texCoord),
                                           object.normalScale, normalMap)
                           : normalize(facingNormal);
  normalGlossiness = vec4(normal, object.specular.a);
  material = packMaterial(object.albedo.rgb * texel.rgb, objectIndex);
}
