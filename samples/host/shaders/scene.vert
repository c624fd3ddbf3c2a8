#version 450
// The host's own geometry shader: object -> clip space, world-space position and normal for its lighting.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(push_constant) uniform Draw {
  mat4 clipFromObject;
  vec4 worldFromObjectRows[3];  // the affine object -> world transform, one row each
  vec4 color;                   // rgb: albedo; a: the weapon mask written to alpha (0 first-person layer, 1 world)
} draw;
layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;

void main() {
  vec4 p = vec4(position, 1.0);
  worldPosition = vec3(dot(draw.worldFromObjectRows[0], p), dot(draw.worldFromObjectRows[1], p),
                       dot(draw.worldFromObjectRows[2], p));
  worldNormal = vec3(dot(draw.worldFromObjectRows[0].xyz, normal), dot(draw.worldFromObjectRows[1].xyz, normal),
                     dot(draw.worldFromObjectRows[2].xyz, normal));
  gl_Position = draw.clipFromObject * p;
}
