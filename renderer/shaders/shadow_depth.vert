#version 450
// Shadow maps: depth only, seen from the light (the object -> light clip matrix comes per draw).
layout(location = 0) in vec3 position;
layout(push_constant) uniform Push { mat4 objectToClip; };

void main() { gl_Position = objectToClip * vec4(position, 1.0); }
