// Tone mapping and display encoding, shared by the resolve and the lighting pass's in-place resolve (include
// after renderer_shared.h).

// Krzysztof Narkowicz's fit of the ACES filmic tone curve (2016).
vec3 filmic(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

vec3 encodeSrgb(vec3 linear) {
  return mix(linear * 12.92, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), linear));
}

// NaN or inf (a broken shader or input) is black, as stereo::sanitizeColor makes it: the curve would turn it
// into NaN and the unorm store into an undefined level that the stereo pass would then displace.
vec4 finiteHdr(vec4 hdr) { return any(isnan(hdr)) || any(isinf(hdr)) ? vec4(0.0) : hdr; }
