// Textures sampled by a compute pass that picks the texture per pixel (the G-buffer resolve of ray-cast
// surfaces): every texture's texels in one storage buffer, filtered as the renderer's texture sampler filters
// them (bilinear, repeat, level 0, sRGB decoded before filtering). A sampler array indexed per pixel would need
// descriptor indexing, which lavapipe lacks. Define S3D_TEXTURE_TABLE_BINDING and S3D_TEXELS_BINDING first.

// Per texture: x its first texel in `texels`, y width, z height, w 1 when sRGB-encoded (Texture::Encoding).
layout(std430, binding = S3D_TEXTURE_TABLE_BINDING) readonly buffer TextureTable { uvec4 textureTable[]; };
layout(std430, binding = S3D_TEXELS_BINDING) readonly buffer Texels { uint texels[]; };  // RGBA8, row by row

float decodeSrgb(float encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : pow((encoded + 0.055) / 1.055, 2.4);
}

vec4 texelOf(uvec4 entry, int x, int y) {
  vec4 texel = unpackUnorm4x8(texels[entry.x + uint(y) * entry.y + uint(x)]);
  if (entry.w != 0u) texel.rgb = vec3(decodeSrgb(texel.r), decodeSrgb(texel.g), decodeSrgb(texel.b));
  return texel;
}

// Repeat addressing for a bilinear tap of a coordinate within one repeat: i in [-1, size], so one wrap each way.
// Not `%`: GLSL leaves a negative operand's remainder undefined, and a GPU was seen to take the tap left of texel 0
// (i = -1) from another column than the last, along the repeat's seam.
int wrapTexel(int i, int size) { return i < 0 ? i + size : (i >= size ? i - size : i); }

vec4 sampleTexels(uint textureIndex, vec2 uv) {
  uvec4 entry = textureTable[textureIndex];  // first texel, width, height, sRGB
  vec2 size = vec2(entry.yz);
  // Only the coordinate within one repeat matters, so a large or non-finite one cannot overflow the index.
  vec2 wrapped = uv - floor(uv);
  if (any(isnan(wrapped)) || any(isinf(wrapped))) wrapped = vec2(0.0);
  vec2 position = wrapped * size - 0.5;
  vec2 corner = floor(position);
  vec2 weight = position - corner;
  int x0 = wrapTexel(int(corner.x), int(entry.y)), x1 = wrapTexel(int(corner.x) + 1, int(entry.y));
  int y0 = wrapTexel(int(corner.y), int(entry.z)), y1 = wrapTexel(int(corner.y) + 1, int(entry.z));
  vec4 top = mix(texelOf(entry, x0, y0), texelOf(entry, x1, y0), weight.x);
  vec4 bottom = mix(texelOf(entry, x0, y1), texelOf(entry, x1, y1), weight.x);
  return mix(top, bottom, weight.y);
}
