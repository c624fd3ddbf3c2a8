// G-buffer pass under visibility shading, objects without textures: the visibility id only (4 bytes a pixel with
// narrow ids); the G-buffer resolve evaluates normal and material from it. On a GPU whose raster side is a small
// part of the chip the pass's cost follows the bytes its fragments write, while compute runs on all of it.
// visibility.frag binds the ids alone; visibility_textured.frag (S3D_VISIBILITY_BESIDE_SURFACE_TARGETS) serves a
// scene whose textured objects write normal and material in the same pass: it writes zeros there, which the
// resolve overwrites (a shader that left them unwritten would store undefined values just the same).
// Include after the #version and renderer_shared.h.

// No discard or depth write here, so the depth test runs before shading (a masked render relies on it).
layout(early_fragment_tests) in;

layout(location = 4) flat in uvec2 visibility;
#ifdef S3D_VISIBILITY_BESIDE_SURFACE_TARGETS
layout(location = 0) out vec4 normalGlossiness;
layout(location = 1) out uvec2 material;
layout(location = 2) out uvec2 visibilityId;  // R32_UINT keeps x
#else
layout(location = 0) out uvec2 visibilityId;  // R32_UINT keeps x
#endif

void main() {
#ifdef S3D_VISIBILITY_BESIDE_SURFACE_TARGETS
  normalGlossiness = vec4(0.0);
  material = uvec2(0u);
#endif
  visibilityId = visibility;
}
