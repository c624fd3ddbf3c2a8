// Listing 4.5's choice of source: the fractional center column a gather (seed, search) filters an eye pixel from.
// Shared by stereo_gather.glsl and the hybrid's classification and base depth, so both follow the gather's own
// choice. The includer declares `c` (maxSeparation, zeroParallaxDistance, width), float depthAt(int x, int y)
// (the sanitized linear depth, edge-clamped), S3D_GATHER_TAP_COUNT and S3D_GATHER_TAP_OFFSET_PX (the taps).

// Minimum depth over the separation range on one side of the pixel.
float minDepthOverTaps(int x, int y, int direction) {
  float minDepth = S3D_INFINITY;  // the seed starts at 1.0, its normalized far plane
  // A compile-time trip count (the array's capacity) with the used count as a guard lets the compiler unroll.
  for (int i = 0; i < S3D_STEREO_TAP_CAPACITY; ++i)
    if (i < S3D_GATHER_TAP_COUNT) minDepth = min(minDepth, depthAt(x + direction * S3D_GATHER_TAP_OFFSET_PX[i], y));
  return minDepth;
}

// The column an eye pixel in column x is filtered from, given its taps' nearest depth (minDepthOverTaps): the left
// eye (direction +1) adds the parallax, the right eye (-1) subtracts it; precise, so every shader and the C++
// reference (gatherSourceColumn) round it alike.
float gatherSourceColumn(int x, int direction, float minDepth) {
  float parallax = parallaxFromDepth(c.maxSeparation, c.zeroParallaxDistance, minDepth);
  precise float column = direction > 0 ? float(x) + parallax * float(c.width) : float(x) - parallax * float(c.width);
  return column;
}

// The center texel nearest a source column (ties to the right, as the classification's nearest landing), clamped to
// the row: where the hybrid's base depth reads the center's device depth.
int nearestSourceTexel(float column) {
  float base = floor(column);
  return clamp(int(base) + (column - base < 0.5 ? 0 : 1), 0, c.width - 1);
}
