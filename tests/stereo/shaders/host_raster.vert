#version 450
// The host-hybrid tests' own raster (test_host_hybrid.cpp): flat-coloured triangles from a camera.
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 vertexColor;
layout(push_constant) uniform Push { mat4 viewProjection; };

void main() {
  gl_Position = viewProjection * vec4(position, 1.0);
  vertexColor = color;
}
