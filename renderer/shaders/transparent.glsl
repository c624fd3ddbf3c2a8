// A transparent surface's colour and opacity before blending, shared by the transparent pass's raster
// (transparent.frag) and compute (transparent.comp) implementations. Forward-lit by hemisphere ambient and the
// sun (point lights are left out: they live in the deferred light buffers). Include after renderer_shared.h and
// material.glsl, with `frame` (FrameConstants) declared.
vec4 shadeTransparent(ObjectConstants object, vec3 worldPosition, vec3 worldNormal, vec4 worldTangent, vec2 texCoord,
                      sampler2D baseColor, sampler2D normalMap) {
  vec3 toEye = normalize(frame.layers[object.layer].worldFromView[3].xyz - worldPosition);
  vec3 normal = shadingNormal(worldNormal, worldTangent, normalMapTexCoord(object, texCoord), object.normalScale, normalMap);
  if (dot(normal, toEye) < 0.0) normal = -normal;  // panes are seen from both sides
  vec3 toSun = frame.directionToSun.xyz;
  float nDotL = max(dot(normal, toSun), 0.0);
  vec3 diffuse = frame.ambientColor.rgb * (normal.y * 0.7 + 0.3) + frame.sunColor.rgb * nDotL;
  float exponent = blinnPhongExponent(object.specular.a);
  vec3 specular = frame.sunColor.rgb * (nDotL * normalizedBlinnPhong(dot(normal, normalize(toSun + toEye)), exponent));
  float nDotV = clamp(dot(normal, toEye), 0.0, 1.0);
  vec3 fresnel = object.specular.rgb + (1.0 - object.specular.rgb) * pow(1.0 - nDotV, 5.0);  // Schlick
  // Specular is not dimmed by the opacity: glass reflects even where it lets most light through.
  // The texture alpha scales the opacity; emission is blended with the surface's colour.
  vec4 albedo = object.albedo * textureLod(baseColor, baseColorTexCoord(object, texCoord), 0.0);
  return vec4(albedo.rgb * diffuse + fresnel * specular / max(albedo.a, 1e-3) + object.emissive.rgb, albedo.a);
}
