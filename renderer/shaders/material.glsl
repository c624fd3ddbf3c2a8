// Material texturing shared by the G-buffer and transparent passes (include after renderer_shared.h).

// Where an object samples its base-colour texture and its normal map (KHR_texture_transform, ObjectConstants).
vec2 baseColorTexCoord(ObjectConstants object, vec2 texCoord) {
  return transformTexCoord(object.baseColorUv, object.uvOffsets.xy, texCoord);
}
vec2 normalMapTexCoord(ObjectConstants object, vec2 texCoord) {
  return transformTexCoord(object.normalUv, object.uvOffsets.zw, texCoord);
}

// The shading normal: the interpolated normal, perturbed by a tangent-space normal map when the object has
// one (normalScale != 0). Without one the result is exactly the untextured renderer's normalize(worldNormal).
// `normalTexel`: the normal map sampled where the surface is.
vec3 shadingNormalFromTexel(vec3 worldNormal, vec4 worldTangent, vec3 normalTexel, float normalScale) {
  vec3 normal = normalize(worldNormal);
  if (normalScale == 0.0) return normal;
  // Gram-Schmidt: the interpolated tangent is re-orthogonalized against the interpolated normal.
  vec3 tangent = normalize(worldTangent.xyz - normal * dot(normal, worldTangent.xyz));
  vec3 bitangent = worldTangent.w * cross(normal, tangent);
  vec3 mapped = normalTexel * 2.0 - 1.0;
  mapped.xy *= normalScale;
  return normalize(tangent * mapped.x + bitangent * mapped.y + normal * mapped.z);
}
vec3 shadingNormal(vec3 worldNormal, vec4 worldTangent, vec2 texCoord, float normalScale, sampler2D normalMap) {
  if (normalScale == 0.0) return normalize(worldNormal);
  // One level: no derivatives needed.
  return shadingNormalFromTexel(worldNormal, worldTangent, textureLod(normalMap, texCoord, 0.0).xyz, normalScale);
}
