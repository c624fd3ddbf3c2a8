// The gathers' output: both eyes' pixel stored in the two eyes, or (from host images) packed straight into the
// target at binding 2. Included after the includer declares leftEye, rightEye and the push constants c (and h).
void writeEyes(ivec2 pixel, vec4 left, vec4 right) {
#ifdef S3D_STEREO_HOST_INPUTS
  if (h.gatherOutput == S3D_HOST_GATHER_ANAGLYPH) {  // 8-bit eyes: mixed from their stored bytes, as the packing pass
    const float byteScale = 1.0 / 255.0;
    vec3 l = round(clamp(left.rgb, 0.0, 1.0) * 255.0) * byteScale, r = round(clamp(right.rgb, 0.0, 1.0) * 255.0) * byteScale;
    l = vec3(hostSrgbToLinear(l.r), hostSrgbToLinear(l.g), hostSrgbToLinear(l.b));
    r = vec3(hostSrgbToLinear(r.r), hostSrgbToLinear(r.g), hostSrgbToLinear(r.b));
    vec3 mixed = clamp(hostDuboisAnaglyph(l, r), 0.0, 1.0);
    imageStore(leftEye, pixel, vec4(hostLinearToSrgb(mixed.r), hostLinearToSrgb(mixed.g), hostLinearToSrgb(mixed.b), 1.0));
    return;
  }
  if (h.gatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL || h.gatherOutput == S3D_HOST_GATHER_TOP_BOTTOM_FULL) {
    imageStore(leftEye, pixel, left);
    imageStore(leftEye, pixel + (h.gatherOutput == S3D_HOST_GATHER_SIDE_BY_SIDE_FULL ? ivec2(c.width, 0) : ivec2(0, c.height)),
               right);
    return;
  }
#endif
  imageStore(leftEye, pixel, left);
  imageStore(rightEye, pixel, right);
}
