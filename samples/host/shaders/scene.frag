#version 450
// The host's own shading: a directional light with ambient over a 1 m checker (texture the eyes can be told apart
// by), written to an sRGB target; alpha carries the weapon mask s3d's HUD fades with.
layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(push_constant) uniform Draw {
  mat4 clipFromObject;
  vec4 worldFromObjectRows[3];
  vec4 color;
} draw;
layout(location = 0) out vec4 outColor;

const vec3 kToLight = vec3(0.41, 0.82, 0.41);

void main() {
  float diffuse = max(dot(normalize(worldNormal), kToLight), 0.0);
  vec3 cell = floor(worldPosition * 2.0 + 1e-3);
  float checker = mod(cell.x + cell.y + cell.z, 2.0);
  vec3 albedo = draw.color.rgb * (0.7 + 0.3 * checker);
  outColor = vec4(albedo * (0.2 + 0.8 * diffuse), draw.color.a);
}
