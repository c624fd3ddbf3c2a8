#pragma once
// The C++ reference of eye views (eye_views.h: OpenXR's per-eye views): one eye synthesized on the CPU from the
// center view that covers both eyes, which the stereo frame's eye views are held to.
#include "s3d/image.h"
#include "s3d/stereo/eye_views.h"

namespace s3d::stereo {

// Iterations of the fixed-point search t_c = t_eye + b / depth(t_c), starting at infinity.
inline constexpr int kViewSearchIterations = 8;

// One eye synthesized from the center view's colour and linear depth (plain C++): per eye pixel centre, the
// depth is found by the fixed-point search, then the colour is filtered bilinearly at the mapped position. When
// `eyeDepth` is given it receives the depth each eye pixel shows (the search's last depth).
ImageRGBA8 synthesizeEyeForView(const ImageRGBA8& centerColor, const DepthImage& centerDepth,
                                const ViewConfiguration& views, const CenterView& center, int eye,
                                DepthImage* eyeDepth = nullptr);

}  // namespace s3d::stereo
