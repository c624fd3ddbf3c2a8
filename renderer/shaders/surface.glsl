// A render pixel's surface point from device depth, and order-preserving float bits for shared-memory
// min/max: the lighting pass and its tile classification (light_tiles.comp). Include after
// renderer_shared.h and the `frame` uniform block.

// Float <-> uint with the same order (negative floats too), for atomicMin/atomicMax.
uint orderedBits(float value) {
  uint bits = floatBitsToUint(value);
  return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}
float orderedFloat(uint bits) {
  return uintBitsToFloat((bits & 0x80000000u) != 0u ? bits & 0x7fffffffu : ~bits);
}

struct Surface {
  vec3 position;  // world
  uint layer;
  float linearDepth;
  vec3 eye;       // the layer's camera position (world)
};

// Listing 4.3, then the view position from the layer's (possibly off-axis) projection, then the world. The
// layer's constants are selected, not indexed: an index varying per pixel is a gather on a CPU rasterizer.
Surface surfaceAt(ivec2 pixel, float device) {
  Surface s;
  bool firstPerson = isFirstPersonDeviceDepth(frame.linearDepth, device);
  s.layer = firstPerson ? S3D_LAYER_FIRST_PERSON : S3D_LAYER_WORLD;
  s.linearDepth = linearDepthFromDepthBuffer(frame.linearDepth, device);
  vec2 ndc = (vec2(pixel) + 0.5) * frame.screen.zw * 2.0 - 1.0;
  vec4 p = firstPerson ? frame.layers[S3D_LAYER_FIRST_PERSON].projection : frame.layers[S3D_LAYER_WORLD].projection;
  vec3 view = vec3((ndc.x + p.z) * s.linearDepth / p.x, (ndc.y + p.w) * s.linearDepth / p.y, -s.linearDepth);
  mat4 worldFromView = firstPerson ? frame.layers[S3D_LAYER_FIRST_PERSON].worldFromView
                                   : frame.layers[S3D_LAYER_WORLD].worldFromView;
  s.position = (worldFromView * vec4(view, 1.0)).xyz;
  s.eye = worldFromView[3].xyz;
  return s;
}
