#version 450
// One triangle covering the screen on the far plane: with depth test LESS_OR_EQUAL it only reaches pixels
// no geometry covered (depth still at its cleared 1.0; reversed-Z: its viewport maps it to 0, GREATER_OR_EQUAL).
void main() {
  vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
}
