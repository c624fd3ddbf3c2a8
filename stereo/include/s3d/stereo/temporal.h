#pragma once
// Temporal stability of a synthesized eye: how much its error changes from one frame to the next along the
// camera's motion (docs/DESIGN.md "Temporal flicker").
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "s3d/image.h"
#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/reprojection_shared.h"

namespace s3d::stereo {

// One eye of one frame as the metric reads it.
struct EyeFrame {
  const ImageRGBA8* synthesized = nullptr;
  const ImageRGBA8* reference = nullptr;       // the eye rendered by the two-pass reference
  const DepthImage* referenceDepth = nullptr;  // its linear depth (+inf: sky)
  // Its first-person pixels (the weapon, which moves with the camera, not with the world); empty: none.
  std::vector<std::uint8_t> firstPerson;
  std::uint32_t cropColumns = 0;  // columns excluded on each side
};

struct FlickerRegion {
  double meanLevels = 0.0;
  std::uint64_t pixelCount = 0;
};

struct FlickerStats {
  FlickerRegion all;           // every compared pixel the previous frame saw
  FlickerRegion halo;          // ... inside the current frame's halo mask
  FlickerRegion disocclusion;  // ... inside the current frame's (stereo) disocclusion mask
  // Compared pixels left out: the camera motion disoccluded them (the previous reference showed another
  // surface there), they came in from outside the previous frame, or their depth is unknown.
  std::uint64_t newlyVisiblePixels = 0;
};

// For every compared pixel x of the current frame whose surface the previous frame showed: the reference eye's
// depth at x puts that surface at x' in the previous frame (`motion`; first-person pixels stay where they are);
// the value is |(S_t(x) - S_t-1(x')) - (R_t(x) - R_t-1(x'))| = |e_t(x) - e_t-1(x')| (e = S - R), 8-bit levels
// averaged over R, G and B, with e_t-1 filtered bilinearly over the texels around x' that show the same surface
// (inverse depth within S3D_REPROJECTION_SAME_SURFACE, same layer, inside the previous crop). An error that sticks
// to the surface as the camera moves scores 0, as does an exact method (and the reference itself) under any
// motion; an error that changes on the surface scores its change. Masks: empty or one entry per pixel.
// Throws std::invalid_argument for images of different sizes or a mask of the wrong size.
FlickerStats temporalFlicker(const EyeFrame& current, const EyeFrame& previous, const gpu::EyeMotion& motion,
                             const std::vector<std::uint8_t>& halo, const std::vector<std::uint8_t>& disocclusion);

// The eye cameras a reference eye was rendered with: one pair of off-axis cameras (the linear mapping), or one
// per segment of a nonlinear map (the per-layer reference: each segment's cameras are exact for its depths) with
// per pixel the layer whose rendering it shows.
struct ReferenceCameras {
  std::vector<glm::mat4> view, projection;       // per layer (at least one)
  std::vector<DisparityMapSegment> segments;     // per layer (disparityMapSegments of the frame's map)
  std::vector<std::uint8_t> layerOfPixel;        // per pixel; empty: every pixel layer 0
};

// The same metric for references rendered in layers: a pixel's surface moves from the camera of the layer that
// rendered it to the previous frame's camera of the layer whose segment holds the surface's previous inverse
// depth (all layers of a frame share the view's depth axis, so that depth is the same under each), where the
// previous reference shows that layer; where it does not (depth edges across segments, pixels no layer claimed),
// to the camera of a layer it does show there. With one layer per frame it is temporalFlicker with eyeMotion of the
// two cameras. Throws std::invalid_argument as above, and for cameras without a layer, lists of different lengths,
// or a layer index or a layer list size that does not match.
FlickerStats temporalFlicker(const EyeFrame& current, const EyeFrame& previous, const ReferenceCameras& currentCameras,
                             const ReferenceCameras& previousCameras, const std::vector<std::uint8_t>& halo,
                             const std::vector<std::uint8_t>& disocclusion);

}  // namespace s3d::stereo
